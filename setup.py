"""The compiled part of grainclass: ``grainclass._voro``, over the Voro++ sources in vendor/."""

import pybind11
from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "grainclass._voro",
            # voro++.cc includes every other source file of the library: one translation unit.
            sources=["src/grainclass/_voro.cpp", "vendor/voro++/src/voro++.cc"],
            include_dirs=[pybind11.get_include(), "vendor/voro++/src"],
            language="c++",
            extra_compile_args=["-std=c++17", "-O3", "-fvisibility=hidden"],
        )
    ]
)
