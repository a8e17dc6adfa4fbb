"""partreg: category-level, part-based, non-rigid 3D registration.

Points are (N, 3), one point per row, in any form robotics code holds them: a numpy float64 or float32 array
of any strides, an Open3D PointCloud (its points) or Vector3dVector, a list of [x, y, z]; anything else raises
partreg.UsageError. Input points are copied once into the library (float32 and strided arrays converted in
that copy; a list is made into a float64 array first); print() of a result says what it holds. Large outputs (deformed points, parts, mesh
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
