"""partreg: category-level, part-based, non-rigid 3D registration.

Points are numpy float64 arrays of shape (N, 3), one point per row, C-contiguous; anything else (float32,
a transposed or strided view, a list) raises partreg.UsageError naming the fix instead of being converted
silently. Input arrays are copied once into the library; large outputs (deformed points, parts, mesh
vertices, shape-space bases) are views of the C++ objects, without a copy: writeable for results (yours),
read-only for a model's arrays (every registration reads them).

Frames: register() works in the observed frame (the frame of the points given, data units); a model's
geometry is in normalised units (canonical diagonal 1), Model.to_data() maps it to the category's data
frame. Poses are 4x4 matrices named T_observed_canonical (canonical data frame -> observed frame).

Errors: partreg.InputError (a RuntimeError) for bad data or a failing resource (missing file, NaN points,
a model of another format version), partreg.UsageError (a ValueError) for a request that can never
succeed as stated (unknown setting, wrong array shape). The messages are the library's own.

Long calls (train, register, cpd, views, file reading) release the interpreter lock.
"""
from ._partreg import *  # noqa: F401,F403
from ._partreg import __version__, model_format_version  # noqa: F401
