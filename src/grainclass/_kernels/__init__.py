"""Compiled kernels: ``@njit`` functions on flat arrays only, no I/O, no pandas.

Everything here is private; :mod:`grainclass.classification` is the public wrapper.
"""
