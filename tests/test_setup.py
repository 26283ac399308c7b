"""Voro++ as a dependency: where setup.py finds it, and grainclass without it."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import EXAMPLES, ROOT
from grainclass.voronoi import INSTALL_VORO


def _load_setup():
    spec = importlib.util.spec_from_file_location("grainclass_setup", ROOT / "setup.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # for its dataclass
    spec.loader.exec_module(module)
    return module


setup = _load_setup()


def _install(prefix: Path, lib: str = "lib", library: str = "libvoro++.so") -> Path:
    """A fake Voro++ under ``prefix``: its main header and a library file in ``lib``."""
    (prefix / "include" / "voro++").mkdir(parents=True)
    (prefix / "include" / "voro++" / "voro++.hh").write_text("// fake\n")
    (prefix / lib).mkdir(parents=True)
    (prefix / lib / library).write_text("")
    return prefix


@pytest.fixture
def environ(tmp_path):
    """An environment in which pkg-config knows only the packages in tmp_path/pkgconfig."""
    (tmp_path / "pkgconfig").mkdir()
    return {"PATH": os.environ["PATH"], "PKG_CONFIG_LIBDIR": str(tmp_path / "pkgconfig")}


def _pc_file(environ: dict, prefix: Path) -> None:
    Path(environ["PKG_CONFIG_LIBDIR"], "voro++.pc").write_text(
        f"prefix={prefix}\nincludedir=${{prefix}}/include\nlibdir=${{prefix}}/lib\n\n"
        "Name: voro++\nDescription: fake\nVersion: 0.4.6\n"
        "Cflags: -I${includedir}/voro++\nLibs: -L${libdir} -lvoro++\n"
    )


@pytest.mark.parametrize(
    ("lib", "library"),
    [
        ("lib", "libvoro++.so"),  # the usual
        ("lib/x86_64-linux-gnu", "libvoro++.so"),  # Debian's multiarch folders
        ("lib64", "libvoro++.so"),
        ("lib", "libvoro++.a"),  # Homebrew's: the static library alone
        ("lib", "libvoro++.dylib"),
    ],
)
def test_a_prefix_holds_voro_with_its_header_and_library(tmp_path, lib, library):
    prefix = _install(tmp_path / "prefix", lib, library)
    found = setup.voro_in_prefix(prefix)
    assert found == setup.VoroInstall(prefix / "include" / "voro++", prefix / lib)


def test_a_header_without_a_library_is_no_voro(tmp_path):
    prefix = _install(tmp_path / "prefix", "lib", "libvoro++.so")
    (prefix / "lib" / "libvoro++.so").unlink()
    assert setup.voro_in_prefix(prefix) is None
    assert setup.voro_in_prefix(tmp_path / "nothing") is None


def test_the_standard_prefixes_are_searched_in_order_then_conda(tmp_path, environ):
    empty, first, second = tmp_path / "empty", tmp_path / "first", tmp_path / "second"
    empty.mkdir()
    _install(first)
    _install(second)
    conda = _install(tmp_path / "conda")
    standard = [str(empty), str(first), str(second)]
    found = setup.find_voro({**environ, "CONDA_PREFIX": str(conda)}, standard)
    assert found.include_dir == first / "include" / "voro++"
    found = setup.find_voro({**environ, "CONDA_PREFIX": str(conda)}, [str(empty)])
    assert found.library_dir == conda / "lib"
    assert setup.find_voro(environ, [str(empty)]) is None


@pytest.mark.skipif(shutil.which("pkg-config") is None, reason="pkg-config is not installed")
def test_pkg_config_comes_before_the_standard_prefixes(tmp_path, environ):
    known = _install(tmp_path / "known")
    standard = _install(tmp_path / "standard")
    _pc_file(environ, known)
    found = setup.find_voro(environ, [str(standard)])
    assert found == setup.VoroInstall(known / "include" / "voro++", known / "lib")


def test_voro_prefix_comes_first_and_must_hold_voro(tmp_path, environ):
    named = _install(tmp_path / "named", "lib64")
    standard = _install(tmp_path / "standard")
    if shutil.which("pkg-config"):
        _pc_file(environ, standard)
    found = setup.find_voro({**environ, "VORO_PREFIX": str(named)}, [str(standard)])
    assert found == setup.VoroInstall(named / "include" / "voro++", named / "lib64")
    with pytest.raises(SystemExit, match=r"VORO_PREFIX=.*holds no Voro"):
        setup.find_voro({**environ, "VORO_PREFIX": str(tmp_path)}, [str(standard)])


def test_setup_and_the_library_name_the_same_packages():
    assert setup.INSTALL_VORO == INSTALL_VORO
    for package in ("apt-get install voro++-dev", "brew install voro++", "conda-forge voro"):
        assert package in INSTALL_VORO


def _without_voro(*args: str) -> subprocess.CompletedProcess:
    """``grainclass ARGS`` where grainclass._voro cannot be imported, as when grainclass was
    installed without Voro++."""
    code = (
        "import sys\n"
        "sys.modules['grainclass._voro'] = None\n"
        "sys.argv = ['grainclass', *sys.argv[1:]]\n"
        "from grainclass.cli import main\n"
        "main()\n"
    )
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True)


@pytest.mark.parametrize("output", ["cells.txt", "cells.parquet"])
def test_without_voro_voronoi_exits_1_naming_the_packages(tmp_path, output):
    seeds = tmp_path / "seeds.txt"
    seeds.write_text("1 0.25 0.25 0.25\n2 0.75 0.75 0.75\n")
    for args in (["100", "--seed", "1"], ["--points", str(seeds)]):
        run = _without_voro("voronoi", *args, "-o", str(tmp_path / output), "-q")
        assert run.returncode == 1
        assert run.stderr.count("\n") == 1, run.stderr
        assert "Voronoi tessellations need the Voro++ library" in run.stderr
        assert INSTALL_VORO in run.stderr
        assert list(tmp_path.iterdir()) == [seeds]


def test_without_voro_the_other_commands_work(tmp_path):
    table = tmp_path / "polytopes.parquet"
    run = _without_voro("classify", str(EXAMPLES / "polytopes.txt"), "-o", str(table), "-q")
    assert run.returncode == 0, run.stderr
    run = _without_voro("summarize", str(table), "--n", "10")
    assert run.returncode == 0, run.stderr
    assert "grains: 13" in run.stdout
