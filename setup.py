"""The compiled part of grainclass: ``grainclass._voro``, over an installed Voro++ library.

Voro++ is found (:func:`find_voro`) under ``VORO_PREFIX`` where that is set, else through
pkg-config where it knows ``voro++``, else under the usual prefixes. Without it grainclass
installs all the same, without ``grainclass._voro``: every command but ``grainclass voronoi``
works, and that one says what to install.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

# Keep in step with grainclass.voronoi.INSTALL_VORO (setup.py cannot import the package).
INSTALL_VORO = (
    "apt-get install voro++-dev (Debian/Ubuntu), brew install voro++ (Homebrew) or "
    "conda install -c conda-forge voro (conda)"
)
STANDARD_PREFIXES = ("/usr", "/usr/local", "/opt/homebrew")
LIBRARY_FILES = ("libvoro++.so", "libvoro++.dylib", "libvoro++.a")
BUILDING = {"bdist_wheel", "editable_wheel", "build_ext", "build", "develop", "install"}


@dataclass(frozen=True)
class VoroInstall:
    """Where Voro++'s headers (``voro++.hh``) and its library are."""

    include_dir: Path
    library_dir: Path


def voro_in_prefix(prefix: Path) -> VoroInstall | None:
    """Voro++ installed under ``prefix`` (``include/voro++/voro++.hh`` and ``libvoro++`` in
    ``lib``, ``lib64`` or a multiarch folder of ``lib``, as Debian has it), or None."""
    include = prefix / "include" / "voro++"
    if not (include / "voro++.hh").is_file():
        return None
    lib = prefix / "lib"
    for folder in (lib, prefix / "lib64", *sorted(lib.glob("*-*-*"))):
        if any((folder / name).exists() for name in LIBRARY_FILES):
            return VoroInstall(include, folder)
    return None


def voro_from_pkg_config(environ: Mapping[str, str]) -> VoroInstall | None:
    """Voro++ as pkg-config knows it (a package named ``voro++``, its ``includedir`` and
    ``libdir``), or None."""
    pkg_config = shutil.which("pkg-config", path=environ.get("PATH"))
    if pkg_config is None:
        return None
    folders = []
    for variable in ("includedir", "libdir"):
        asked = subprocess.run(
            [pkg_config, f"--variable={variable}", "voro++"],
            capture_output=True,
            text=True,
            check=False,
            env=dict(environ),
        )
        if asked.returncode != 0 or not asked.stdout.strip():
            return None
        folders.append(Path(asked.stdout.strip()))
    include, library = folders
    for headers in (include / "voro++", include):
        if (headers / "voro++.hh").is_file():
            return VoroInstall(headers, library)
    return None


def find_voro(
    environ: Mapping[str, str] = os.environ,
    standard_prefixes: Sequence[str] = STANDARD_PREFIXES,
) -> VoroInstall | None:
    """Where Voro++ is installed, or None: under ``VORO_PREFIX`` when it is set (nowhere else:
    a prefix named on purpose that lacks Voro++ is an error, SystemExit), else where pkg-config
    says, else under the standard prefixes and ``$CONDA_PREFIX``, in that order."""
    named = environ.get("VORO_PREFIX")
    if named:
        found = voro_in_prefix(Path(named))
        if found is None:
            raise SystemExit(
                f"grainclass: VORO_PREFIX={named} holds no Voro++ "
                "(include/voro++/voro++.hh and lib/libvoro++)"
            )
        return found
    found = voro_from_pkg_config(environ)
    if found is not None:
        return found
    conda = environ.get("CONDA_PREFIX")
    for prefix in (*standard_prefixes, *([conda] if conda else [])):
        found = voro_in_prefix(Path(prefix))
        if found is not None:
            return found
    return None


def voro_extension(voro: VoroInstall):
    """``grainclass._voro``, compiled against Voro++ at ``voro``."""
    import pybind11
    from setuptools import Extension

    return Extension(
        "grainclass._voro",
        sources=["src/grainclass/_voro.cpp"],
        include_dirs=[pybind11.get_include(), str(voro.include_dir)],
        library_dirs=[str(voro.library_dir)],
        libraries=["voro++"],
        runtime_library_dirs=[str(voro.library_dir)],
        language="c++",
        extra_compile_args=["-std=c++17", "-O3", "-fvisibility=hidden"],
    )


def main() -> None:
    from setuptools import setup

    voro = find_voro()
    # setup.py runs for the metadata too: what was found is said where the wheel is built.
    if BUILDING.intersection(sys.argv):
        if voro is None:
            print(
                "grainclass: Voro++ not found, building without grainclass._voro (`grainclass "
                f"voronoi` needs it): {INSTALL_VORO}, or set VORO_PREFIX",
                file=sys.stderr,
            )
        else:
            print(
                f"grainclass: Voro++ from {voro.include_dir} and {voro.library_dir}",
                file=sys.stderr,
            )
    setup(ext_modules=[] if voro is None else [voro_extension(voro)])


if __name__ == "__main__":
    main()
