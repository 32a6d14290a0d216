"""Training of the bundled sign detector (``models/roadsigns.onnx``); needs PyTorch (CPU),
never shipped in the plugin. ``python -m devtools.train --minutes 40 --out models/roadsigns.onnx``."""
