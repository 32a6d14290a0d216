"""Rewritten ONNX files: a session of one in memory, its metadata entries, and writing it
under a temporary name in the target's folder, then renamed."""
from __future__ import annotations

import os
import tempfile


def save_model(model, out_path: str) -> None:
    """Save ``model`` (an ``onnx.ModelProto``) to ``out_path``, which may be the file it was read
    from: written beside it under a temporary name, given the umask's permissions, renamed."""
    import onnx

    fd, tmp = tempfile.mkstemp(suffix=".onnx", dir=os.path.dirname(os.path.abspath(out_path)))
    os.close(fd)
    try:
        onnx.save(model, tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)          # mkstemp makes it private
        os.replace(tmp, out_path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def cpu_session(model):
    """A quiet onnxruntime CPU session of ``model`` (an ``onnx.ModelProto``), from memory."""
    import onnxruntime as ort

    options = ort.SessionOptions()
    options.log_severity_level = 3
    return ort.InferenceSession(model.SerializeToString(), sess_options=options, providers=["CPUExecutionProvider"])


def set_metadata(model, key: str, value: str) -> None:
    """Set the metadata entry ``key`` of ``model`` to ``value``, adding it when missing."""
    for entry in model.metadata_props:
        if entry.key == key:
            entry.value = value
            return
    model.metadata_props.add(key=key, value=value)
