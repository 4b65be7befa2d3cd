"""Where the compiled route finds scikit-sundae's SUNDIALS libraries on each platform, and how it
refuses a platform or build it cannot serve: one warning, then the Python route (#14).

The fake folders hold empty files named exactly as in scikit-sundae 1.2.0's cp311 wheels (the
libraries' folders listed in full), so the locator is tested on every layout without loading
anything; only the Linux libraries are loaded, here."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from circuitsim.solve import sundials_libs
from circuitsim.solve.sundials_libs import LibrariesUnavailable, library_paths

_MAC_SUNDIALS = [f"libsundials_{name}.{version}.dylib" for name, version in (
    ("core", "7.9.0"), ("cvode", "7.9.0"), ("ida", "7.9.0"), ("nvecserial", "7.9.0"),
    ("sunlinsolband", "5.9.0"), ("sunlinsoldense", "5.9.0"), ("sunlinsollapackband", "5.9.0"),
    ("sunlinsollapackdense", "5.9.0"), ("sunlinsolspbcgs", "5.9.0"),
    ("sunlinsolspgmr", "5.9.0"), ("sunlinsolsptfqmr", "5.9.0"),
    ("sunlinsolsuperlumt", "5.9.0"), ("sunmatrixband", "5.9.0"),
    ("sunmatrixdense", "5.9.0"), ("sunmatrixsparse", "5.9.0"))]

#: wheel: (sys.platform, the libraries' folder, every file in it, the extension modules)
WHEELS = {
    "manylinux2014_x86_64": ("linux", "scikit_sundae.libs", [
        "libgfortran-8b93406a.so.5.0.0", "libgomp-34324e08.so.1.0.0",
        "libopenblasp-r0-f1424288.3.34.so", "libquadmath-9fa48070.so.0.0.0",
        "libsundials_core-943007ef.so.7.9.0", "libsundials_cvode-cf29dc23.so.7.9.0",
        "libsundials_ida-16d992eb.so.7.9.0", "libsundials_nvecserial-9988a993.so.7.9.0",
        "libsundials_sunlinsolband-1ad50abe.so.5.9.0",
        "libsundials_sunlinsoldense-9a8418e7.so.5.9.0",
        "libsundials_sunlinsollapackband-fbc3584d.so.5.9.0",
        "libsundials_sunlinsollapackdense-779ad982.so.5.9.0",
        "libsundials_sunlinsolspbcgs-82201096.so.5.9.0",
        "libsundials_sunlinsolspgmr-cff8bbdc.so.5.9.0",
        "libsundials_sunlinsolsptfqmr-9b6f797a.so.5.9.0",
        "libsundials_sunlinsolsuperlumt-93eece90.so.5.9.0",
        "libsundials_sunmatrixband-d4ff3f7f.so.5.9.0",
        "libsundials_sunmatrixdense-8c90dba9.so.5.9.0",
        "libsundials_sunmatrixsparse-bedc6ca1.so.5.9.0"],
        ["_cy_common.cpython-311-x86_64-linux-gnu.so", "_cy_ida.cpython-311-x86_64-linux-gnu.so"]),
    "macosx_11_0_arm64": ("darwin", "sksundae/.dylibs", [
        "libgcc_s.1.1.dylib", "libgfortran.5.dylib", "libomp.dylib", "libopenblas.0.dylib",
        "libquadmath.0.dylib", *_MAC_SUNDIALS],
        ["_cy_common.cpython-311-darwin.so", "_cy_ida.cpython-311-darwin.so"]),
    "macosx_11_0_x86_64": ("darwin", "sksundae/.dylibs", [
        "libgcc_s.1.1.dylib", "libgfortran.5.dylib", "libomp.dylib",
        "libopenblasp-r0.3.34.dylib", "libquadmath.0.dylib", *_MAC_SUNDIALS],
        ["_cy_common.cpython-311-darwin.so", "_cy_ida.cpython-311-darwin.so"]),
    "win_amd64": ("win32", "scikit_sundae.libs", [
        "libblas-c2567feb14c731f582929f36be6d56b5.dll",
        "liblapack-91e7e84358229a902aca9efdd6b87e5b.dll", "openblas.dll",
        "sundials_core-db7c109a212c741d607a8303de169253.dll",
        "sundials_cvode-163885f2d7d421bf831611461f98851c.dll",
        "sundials_ida-5aa2d08e41de3a4b67f04e6ba7bea2e4.dll",
        "sundials_nvecserial-ad0f5d5b3c1c1d3204826466352222c4.dll",
        "sundials_sunlinsolband-82d007d44336704120707e490f39a4da.dll",
        "sundials_sunlinsoldense-47108f1fb8584c4fcbff7d7a64e5ec45.dll",
        "sundials_sunlinsollapackband-a10275aa730adf20da320f76629c2f82.dll",
        "sundials_sunlinsollapackdense-5eb90c4fa755de369bd363b8b295c83d.dll",
        "sundials_sunlinsolspbcgs-b3e6ca219ea99c870c9789d28945c7d7.dll",
        "sundials_sunlinsolspgmr-68905c1a2559257f493e631e5e468e01.dll",
        "sundials_sunlinsolsptfqmr-9a38d3df6de649ce1ae708eefd0aae4d.dll",
        "sundials_sunlinsolsuperlumt-90b903d35971298b1f6f991e9178138b.dll",
        "sundials_sunmatrixband-2d8dabf797bfb82702edd904d551e9d4.dll",
        "sundials_sunmatrixdense-348f0d582c503317e1167d56c67b3b40.dll",
        "sundials_sunmatrixsparse-493bc227ecc028248012d9477a3f649c.dll",
        "vcomp140-95d4ce4a6802d1e18b5e0e1722cc30ea.dll"],
        ["_cy_common.cp311-win_amd64.pyd", "_cy_ida.cp311-win_amd64.pyd"]),
}

#: each wheel's file for IDA, the library the route cannot do without
IDA_FILE = {"manylinux2014_x86_64": "libsundials_ida-16d992eb.so.7.9.0",
            "macosx_11_0_arm64": "libsundials_ida.7.9.0.dylib",
            "macosx_11_0_x86_64": "libsundials_ida.7.9.0.dylib",
            "win_amd64": "sundials_ida-5aa2d08e41de3a4b67f04e6ba7bea2e4.dll"}

#: scikit-sundae 1.2.0's record of its build (``sksundae._cy_common.config``), the same in all
#: four wheels
CONFIG = {"SUNDIALS_VERSION": "7.9.0", "SUNDIALS_FLOAT_TYPE": "double",
          "SUNDIALS_INT_TYPE": "int", "SUNDIALS_SUPERLUMT_ENABLED": "True",
          "SUNDIALS_SUPERLUMT_THREAD_TYPE": "OPENMP", "SUNDIALS_BLAS_LAPACK_ENABLED": "True"}


def _site(tmp_path: Path, wheel: str) -> Path:
    """A site-packages folder holding the wheel's libraries and extension modules, all empty."""
    _platform, folder, files, modules = WHEELS[wheel]
    for name in files:
        (tmp_path / folder).mkdir(parents=True, exist_ok=True)
        (tmp_path / folder / name).touch()
    for name in modules:
        (tmp_path / "sksundae").mkdir(exist_ok=True)
        (tmp_path / "sksundae" / name).touch()
    return tmp_path


@pytest.mark.parametrize("wheel", sorted(WHEELS))
def test_each_wheel_layout_is_found(tmp_path, wheel):
    """Every library in its folder, each by its own name: sunlinsolband is not
    sunlinsollapackband, sunmatrixdense not sunlinsoldense."""
    platform, folder, files, _modules = WHEELS[wheel]
    paths = library_paths(_site(tmp_path, wheel), platform)
    assert sorted(paths) == sorted(sundials_libs.NAMES)
    assert paths["ida"] == tmp_path / folder / IDA_FILE[wheel]
    for name, path in paths.items():
        assert path.name in files and path.parent == tmp_path / folder
        stem = path.name.removeprefix("lib").removeprefix("sundials_")
        assert stem.split("-")[0].split(".")[0] == name


@pytest.mark.parametrize("wheel", sorted(WHEELS))
def test_another_platforms_layout_is_not_taken(tmp_path, wheel):
    """A folder laid out for one platform serves no other."""
    site = _site(tmp_path, wheel)
    for platform in {"linux", "darwin", "win32"} - {WHEELS[wheel][0]}:
        with pytest.raises(LibrariesUnavailable, match="sundials_core"):
            library_paths(site, platform)


def test_an_unknown_platform_is_refused(tmp_path):
    with pytest.raises(LibrariesUnavailable, match="platform 'freebsd14'"):
        library_paths(_site(tmp_path, "manylinux2014_x86_64"), "freebsd14")


def test_a_missing_library_is_named(tmp_path):
    site = _site(tmp_path, "win_amd64")
    (site / "scikit_sundae.libs" / IDA_FILE["win_amd64"]).unlink()
    with pytest.raises(LibrariesUnavailable, match=r"no sundials_ida-\*\.dll in"):
        library_paths(site, "win32")


def test_two_builds_side_by_side_are_refused(tmp_path):
    site = _site(tmp_path, "manylinux2014_x86_64")
    (site / "scikit_sundae.libs" / "libsundials_ida-0123abcd.so.7.8.0").touch()
    with pytest.raises(LibrariesUnavailable, match="2 files matching libsundials_ida"):
        library_paths(site, "linux")


@pytest.mark.parametrize("key, value, why", [
    ("SUNDIALS_INT_TYPE", "long int", "32-bit indices"),
    ("SUNDIALS_INT_TYPE", "int64_t", "32-bit indices"),
    ("SUNDIALS_VERSION", "6.7.0", "SUNDIALS 7's struct layouts"),
    ("SUNDIALS_FLOAT_TYPE", "float", "sunrealtype 'float'")])
def test_another_build_is_refused(key, value, why):
    sundials_libs.check_build(CONFIG)
    sundials_libs.check_build(None)  # no record: the layout check decides
    with pytest.raises(LibrariesUnavailable, match=why):
        sundials_libs.check_build({**CONFIG, key: value})


linux_only = pytest.mark.skipif(sys.platform != "linux",
                                reason="the libraries are loaded on Linux only")


def test_the_checked_fields_are_the_ones_the_kernels_read():
    """check_layouts compares the offsets written into codegen's field intrinsics, no others."""
    import re

    from circuitsim.solve.kernel_lib import SOURCE as _KERNEL_LIB

    read = {(int(offset), "ptr" if pointer else "int") for offset, pointer in re.findall(
        r"_band_field\((\d+), ir\.IntType\(\d+\)(\.as_pointer\(\))?\)", _KERNEL_LIB)}
    assert "ir.Constant(ir.IntType(64), 8)" in _KERNEL_LIB  # data_of: pointer at 8
    read.add((8, "ptr"))
    assert read == {(offset, width) for _kind, offset, width, _name in sundials_libs.FIELDS}


@linux_only
@pytest.mark.parametrize("k", range(len(sundials_libs.FIELDS)))
def test_each_field_is_checked_on_the_installed_libraries(monkeypatch, k):
    """This installation's libraries, found by the same locator, pass the layout check; any
    one field read elsewhere in its struct (here at its start, where a length or size is)
    fails it, naming that field's accessor."""
    pytest.importorskip("numba")
    from circuitsim.solve import direct

    lib = direct._libraries()
    sundials_libs.check_layouts(lib)
    fields = list(sundials_libs.FIELDS)
    kind, _offset, width, name = fields[k]
    fields[k] = (kind, 0, width, name)
    monkeypatch.setattr(sundials_libs, "FIELDS", tuple(fields))
    with pytest.raises(LibrariesUnavailable, match=f"not laid out .*{name.split('.')[1]}"):
        sundials_libs.check_layouts(lib)


_PULSE = """
    components:
      - {name: V1, type: V, p: a, n: gnd, V: {pulse: {v1: 0, v2: 5, delay: 1 ms,
         rise: 10 us, fall: 10 us, width: 2 ms, period: 5 ms}}}
      - {name: R1, type: R, p: a, n: b, R: 1k}
      - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
    probes: {vc: b.v}
    analysis: {stop: 12 ms, step: 10 us}
"""


@pytest.fixture
def fresh_route(monkeypatch):
    """The route with nothing loaded, warned or refused yet, and the same again after."""
    pytest.importorskip("numba")
    from circuitsim.solve import direct

    monkeypatch.setattr(direct, "_LOADED", {})
    monkeypatch.setattr(direct, "_WARNED", set())
    direct._libraries.cache_clear()
    yield direct
    direct._libraries.cache_clear()


def _refused(monkeypatch, how: str) -> str:
    """Make this installation look like one the route cannot serve; the reason expected."""
    if how == "no layout":
        monkeypatch.setattr(sundials_libs, "LAYOUTS", {})
        return f"no scikit-sundae wheel layout is known for platform '{sys.platform}'"
    if how == "no libraries":
        monkeypatch.setitem(sundials_libs.LAYOUTS, sys.platform, ("gone", "sundials_{}.x"))
        return "no sundials_core.x in"
    from sksundae import _cy_common

    monkeypatch.setitem(_cy_common.config, "SUNDIALS_INT_TYPE", "long int")
    return "sunindextype 'long int'"


@pytest.mark.parametrize("how", ["no layout", "no libraries", "64-bit indices"])
def test_a_refused_platform_warns_once_and_runs_the_python_route(
        compile_text, monkeypatch, fresh_route, how):
    """Two runs of a model integrated in several segments (a pulse source's corners): one
    warning naming the reason and the Python route, and the Python route's very numbers."""
    from circuitsim.errors import CircuitWarning

    model = compile_text(_PULSE)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    python = model.simulate()
    why = _refused(monkeypatch, how)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        runs = [model.simulate(), model.simulate()]
    said = [str(w.message) for w in caught if issubclass(w.category, CircuitWarning)
            and "compiled kernels unavailable" in str(w.message)]
    assert len(said) == 1 and why in said[0] and "the Python residual is used" in said[0]
    assert fresh_route._LOADED.get(model.key) is None  # the kernels did not run
    for run in runs:
        assert (run.nfev, run.njev) == (python.nfev, python.njev)
        for a, b in ((run.t, python.t), (run.y, python.y), (run.yp, python.yp)):
            assert np.array_equal(a, b)
