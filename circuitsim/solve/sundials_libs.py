"""scikit-sundae's private SUNDIALS libraries for the compiled route (``solve/direct.py``): where
each platform's wheel keeps them, their ctypes signatures, and the checks that they are the
build whose struct layouts the kernels read.

Inspected in scikit-sundae 1.2.0's cp311 wheels (SUNDIALS 7.9.0), one library for each:

- Linux, manylinux2014 / manylinux_2_28 x86_64 (auditwheel):
  ``scikit_sundae.libs/libsundials_ida-16d992eb.so.7.9.0``
- macOS, macosx_11_0_arm64 and macosx_11_0_x86_64 (delocate 0.13.0):
  ``sksundae/.dylibs/libsundials_ida.7.9.0.dylib``
- Windows, win_amd64 (delvewheel 1.13.2):
  ``scikit_sundae.libs/sundials_ida-5aa2d08e41de3a4b67f04e6ba7bea2e4.dll``

In all four, ``sunindextype`` is 32-bit and the fields the kernels read sit at the same offsets
(the accessors' machine code: ``N_VGetLength_Serial`` loads 32 bits, ``N_VGetArrayPointer_Serial``
and ``SUNDenseMatrix_Data`` read offset 8, ``SUNBandMatrix_LDim`` 8 (32 bits),
``SUNBandMatrix_StoredUpperBandwidth`` 20 (32 bits), ``SUNBandMatrix_Data`` 24,
``SUNSparseMatrix_Data`` / ``_IndexValues`` / ``_IndexPointers`` 16 / 32 / 40), and the
package's own build record (``sksundae._cy_common.config``) says ``SUNDIALS_INT_TYPE = "int"``.
Only the Linux one is executed here; ``check_layouts`` repeats the offset check at run time on
whichever libraries load, so another build refuses the route instead of giving wrong numbers.
"""

from __future__ import annotations

import ctypes
import os
from pathlib import Path
from typing import Any

#: the SUNDIALS libraries the route calls, by SUNDIALS' short names
NAMES = ("core", "nvecserial", "sunmatrixdense", "sunlinsoldense", "sunmatrixband",
         "sunlinsolband", "sunmatrixsparse", "sunlinsolsuperlumt", "ida")

#: per ``sys.platform``: the libraries' folder in site-packages and their file names, as the
#: wheels' repair tools leave them (auditwheel and delvewheel add a hash, delocate does not)
LAYOUTS = {
    "linux": ("scikit_sundae.libs", "libsundials_{}-*.so*"),
    "darwin": ("sksundae/.dylibs", "libsundials_{}.*.dylib"),
    "win32": ("scikit_sundae.libs", "sundials_{}-*.dll"),
}

#: the build the kernels are written for (codegen's field offsets assume all three)
SUNDIALS_MAJOR, INDEX_TYPE, REAL_TYPE = "7", "int", "double"

#: os.add_dll_directory's handles, kept: closing one takes its folder off the search path
_DLL_DIRECTORIES: list[Any] = []


class LibrariesUnavailable(RuntimeError):
    """This installation's SUNDIALS cannot serve the compiled kernels; the message says why."""


def library_paths(site: Path, platform: str) -> dict[str, Path]:
    """Each library's file in ``platform``'s wheel layout under ``site`` (the folder holding
    ``sksundae``). Only lists folders: loads nothing. Exactly one file must match a name (two
    would mean two builds side by side, either of which the kernels might not fit)."""
    if platform not in LAYOUTS:
        raise LibrariesUnavailable(f"no scikit-sundae wheel layout is known for platform "
                                   f"{platform!r} (known: {', '.join(LAYOUTS)})")
    folder, pattern = LAYOUTS[platform]
    where = site / folder
    found = {}
    for name in NAMES:
        files = sorted(where.glob(pattern.format(name)))
        if len(files) != 1:
            count = "no" if not files else f"{len(files)} files matching"
            raise LibrariesUnavailable(f"{count} {pattern.format(name)} in {where}")
        found[name] = files[0]
    return found


def check_build(config: dict | None) -> None:
    """Refuse a SUNDIALS built otherwise than the kernels read it, from scikit-sundae's record
    of the ``sundials_config.h`` it was built against (``sksundae._cy_common.config``; without
    one, ``check_layouts`` alone decides)."""
    if config is None:
        return
    version = str(config.get("SUNDIALS_VERSION", ""))
    if version.split(".")[0] != SUNDIALS_MAJOR:
        raise LibrariesUnavailable(f"SUNDIALS {version}: the kernels read SUNDIALS "
                                   f"{SUNDIALS_MAJOR}'s struct layouts")
    index = config.get("SUNDIALS_INT_TYPE")
    if index != INDEX_TYPE:
        raise LibrariesUnavailable(f"SUNDIALS built with sunindextype {index!r}: the kernels "
                                   f"and signatures take 32-bit indices ({INDEX_TYPE!r})")
    real = config.get("SUNDIALS_FLOAT_TYPE")
    if real != REAL_TYPE:
        raise LibrariesUnavailable(f"SUNDIALS built with sunrealtype {real!r}, not "
                                   f"{REAL_TYPE!r}")


def load(paths: dict[str, Path], platform: str) -> dict[str, Any]:
    """The libraries at ``paths``, with the signatures used by the route. scikit-sundae's own
    modules have loaded them already, so these are the same images, not second copies."""
    if platform == "win32":
        # dependants (sundials_ida-*.dll needs sundials_core-*.dll) are found in this folder:
        # scikit-sundae's delvewheel patch adds it on import, and this keeps it there
        _DLL_DIRECTORIES.append(os.add_dll_directory(str(paths["core"].parent)))
    # RTLD_GLOBAL (no effect on Windows): the symbols serve LLVM's search too
    lib = {name: ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL) for name, path in paths.items()}
    # sunindextype is int in every wheel inspected (check_build); long int is C's long, which
    # ctypes' c_long follows (32-bit on Windows, as SUNDIALS' own long there)
    vp, dbl, i32, lng = ctypes.c_void_p, ctypes.c_double, ctypes.c_int, ctypes.c_long
    for name, res, args in _signatures(vp, dbl, i32, lng):
        owner, fn = name.split(".")
        f = getattr(lib[owner], fn)
        f.restype, f.argtypes = res, args
    return lib


def _signatures(vp, dbl, i32, lng) -> list:
    """(library.function, result type, argument types) of every function called."""
    ptr = ctypes.POINTER
    return [("core.SUNContext_Create", i32, [i32, ptr(vp)]),
            ("core.SUNContext_ClearErrHandlers", i32, [vp]),
            ("core.SUNContext_Free", i32, [ptr(vp)]),
            ("core.N_VGetArrayPointer", ptr(dbl), [vp]), ("core.N_VDestroy", None, [vp]),
            ("core.SUNMatDestroy", None, [vp]), ("core.SUNLinSolFree", i32, [vp]),
            ("nvecserial.N_VNew_Serial", vp, [i32, vp]),
            ("sunmatrixdense.SUNDenseMatrix", vp, [i32, i32, vp]),
            ("sunmatrixdense.SUNDenseMatrix_Data", vp, [vp]),
            ("sunlinsoldense.SUNLinSol_Dense", vp, [vp, vp, vp]),
            ("sunmatrixband.SUNBandMatrix", vp, [i32, i32, i32, vp]),
            ("sunmatrixband.SUNBandMatrix_Data", vp, [vp]),
            ("sunmatrixband.SUNBandMatrix_LDim", i32, [vp]),
            ("sunmatrixband.SUNBandMatrix_StoredUpperBandwidth", i32, [vp]),
            ("sunlinsolband.SUNLinSol_Band", vp, [vp, vp, vp]),
            ("sunmatrixsparse.SUNSparseMatrix", vp, [i32, i32, i32, i32, vp]),
            ("sunmatrixsparse.SUNSparseMatrix_Data", vp, [vp]),
            ("sunmatrixsparse.SUNSparseMatrix_IndexValues", vp, [vp]),
            ("sunmatrixsparse.SUNSparseMatrix_IndexPointers", vp, [vp]),
            ("sunlinsolsuperlumt.SUNLinSol_SuperLUMT", vp, [vp, vp, i32, vp]),
            ("ida.IDACreate", vp, [vp]), ("ida.IDAInit", i32, [vp, vp, dbl, vp, vp]),
            ("ida.IDAFree", None, [ptr(vp)]), ("ida.IDASStolerances", i32, [vp, dbl, dbl]),
            ("ida.IDASetLinearSolver", i32, [vp, vp, vp]), ("ida.IDASetJacFn", i32, [vp, vp]),
            ("ida.IDASetUserData", i32, [vp, vp]), ("ida.IDASetMaxNumSteps", i32, [vp, lng]),
            ("ida.IDASetMaxStep", i32, [vp, dbl]), ("ida.IDASetId", i32, [vp, vp]),
            ("ida.IDASetStopTime", i32, [vp, dbl]),
            ("ida.IDARootInit", i32, [vp, i32, vp]),
            ("ida.IDASetRootDirection", i32, [vp, vp]),
            ("ida.IDAGetRootInfo", i32, [vp, vp]),
            ("ida.IDASolve", i32, [vp, dbl, ptr(dbl), vp, vp, i32]),
            ("ida.IDAGetNumResEvals", i32, [vp, ptr(lng)]),
            ("ida.IDAGetNumJacEvals", i32, [vp, ptr(lng)])]


#: the content fields the kernels read (``compiler/codegen.py``: data_of, band_ldim, band_smu,
#: band_data, sparse_data, sparse_rows, sparse_ptrs): object, byte offset, 32-bit integer or
#: pointer, and the library's accessor for it
FIELDS = (("vector", 8, "ptr", "core.N_VGetArrayPointer"),
          ("dense", 8, "ptr", "sunmatrixdense.SUNDenseMatrix_Data"),
          ("band", 8, "int", "sunmatrixband.SUNBandMatrix_LDim"),
          ("band", 20, "int", "sunmatrixband.SUNBandMatrix_StoredUpperBandwidth"),
          ("band", 24, "ptr", "sunmatrixband.SUNBandMatrix_Data"),
          ("sparse", 16, "ptr", "sunmatrixsparse.SUNSparseMatrix_Data"),
          ("sparse", 32, "ptr", "sunmatrixsparse.SUNSparseMatrix_IndexValues"),
          ("sparse", 40, "ptr", "sunmatrixsparse.SUNSparseMatrix_IndexPointers"))


def check_layouts(lib: dict[str, Any]) -> None:
    """Read every field the kernels read, at the kernels' offsets, in small objects made by the
    libraries, and compare with the libraries' own accessors: a build laid out otherwise (64-bit
    indices, another SUNDIALS) raises LibrariesUnavailable before any kernel runs."""
    core, ctx = lib["core"], ctypes.c_void_p()
    if core.SUNContext_Create(0, ctypes.byref(ctx)) != 0:
        raise LibrariesUnavailable("SUNDIALS' SUNContext_Create failed")
    # a 9 x 9 band matrix of upper / lower bandwidth 1 / 2: ldim 6 and stored upper bandwidth 3
    # differ from its size, so a field read one slot off shows
    objects = {"vector": lib["nvecserial"].N_VNew_Serial(3, ctx),
               "dense": lib["sunmatrixdense"].SUNDenseMatrix(3, 4, ctx),
               "band": lib["sunmatrixband"].SUNBandMatrix(9, 1, 2, ctx),
               "sparse": lib["sunmatrixsparse"].SUNSparseMatrix(3, 3, 4, 0, ctx)}
    try:
        if not all(objects.values()):
            raise LibrariesUnavailable("SUNDIALS could not make a vector or matrix")
        wrong = [accessor for kind, offset, width, accessor in FIELDS
                 if _field(objects[kind], offset, width) != _accessed(lib, accessor, objects[kind])]
    finally:
        if objects["vector"]:
            core.N_VDestroy(objects["vector"])
        for kind in ("dense", "band", "sparse"):
            if objects[kind]:
                core.SUNMatDestroy(objects[kind])
        core.SUNContext_Free(ctypes.byref(ctx))
    if wrong:
        raise LibrariesUnavailable(f"SUNDIALS' structs are not laid out as the kernels read "
                                   f"them ({', '.join(wrong)} disagree)")


def _field(obj: int, offset: int, width: str) -> int | None:
    """The field at ``offset`` in the content of a SUNDIALS object (its first member)."""
    content = ctypes.c_void_p.from_address(obj).value
    if width == "int":
        return ctypes.c_int32.from_address(content + offset).value
    return ctypes.c_void_p.from_address(content + offset).value


def _accessed(lib: dict[str, Any], accessor: str, obj: int) -> int | None:
    """What the library's accessor returns for ``obj`` (a pointer as an address)."""
    owner, fn = accessor.split(".")
    value = getattr(lib[owner], fn)(obj)
    if isinstance(value, ctypes.POINTER(ctypes.c_double)):  # N_VGetArrayPointer's double *
        return ctypes.cast(value, ctypes.c_void_p).value
    return value
