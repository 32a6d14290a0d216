"""The engine of Road Sign Inventory: plain Python, numpy arrays in and out, no qgis import.

Modules, one concern each: ``geometry`` (frames, rotations, pixel <-> ray), ``crs``
(pyproj transforms, meridian convergence), ``tables`` (delimited text input),
``trajectory`` (trajectory/SBET/poses -> panorama stations), ``panorama`` (image files and
perspective views cut from them), ``detector`` (ONNX models: layouts, NMS, merging views),
``pointcloud`` (chunked LAS/LAZ I/O, crop, tiled index), ``ground`` (ground filter engines),
``evaluate`` (matching against reference signs, report), ``errors`` (the exceptions and the
progress/cancel protocol every stage takes).
"""
