"""Writing a rewritten ONNX file: under a temporary name in the target's folder, then renamed."""
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
