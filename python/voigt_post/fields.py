"""A run's fields: the datasets of one HDF5 output (fields_NNNNNN.h5, listed in fields.xdmf:
voigt_post.xdmf) or checkpoint, as numpy arrays in the file's (z, y, x[, component]) order.

h5py (Debian python3-h5py, scripts/setup --figures) when it is installed; otherwise h5ls and
h5dump (hdf5-tools, scripts/setup) read the same doubles. Voigt writes cell fields with
(nz, ny, nx) points and node fields with (nz + 1, ny + 1, nx + 1), vectors with a last axis of 3.

    from voigt_post import fields, xdmf
    psi = fields.read(xdmf.frames("output/run")[-1].path, "psi")
"""
import os
import subprocess
import tempfile


def _h5py():
    try:
        import h5py
        return h5py
    except ImportError:
        return None


def read(path, name):
    """Dataset `name` ("psi" or "/psi") of the HDF5 file `path` as a float64 numpy array."""
    import numpy as np
    name = "/" + name.lstrip("/")
    h5py = _h5py()
    if h5py is not None:
        with h5py.File(path, "r") as f:
            return np.array(f[name])
    listing = subprocess.run(["h5ls", path + name], capture_output=True, text=True, check=True).stdout
    dims = [int(x) for x in listing.split("{", 1)[1].split("}", 1)[0].replace("/Inf", "").split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        raw = os.path.join(tmp, "data.bin")
        subprocess.run(["h5dump", "-d", name, "-b", "LE", "-o", raw, path], check=True, stdout=subprocess.DEVNULL)
        return np.fromfile(raw, dtype="<f8").reshape(dims)


def names(path):
    """The top-level dataset names of the file."""
    h5py = _h5py()
    if h5py is not None:
        with h5py.File(path, "r") as f:
            return sorted(f.keys())
    out = subprocess.run(["h5ls", path], capture_output=True, text=True, check=True).stdout
    return sorted(line.split()[0] for line in out.splitlines() if line.strip())


def mid_z(path, name):
    """The (y, x) slice of a cell field at the middle z layer."""
    a = read(path, name)
    return a[a.shape[0] // 2]
