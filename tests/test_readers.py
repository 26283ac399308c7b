"""The readers package: one reader per input format, and the names other modules import."""

from __future__ import annotations

from grainclass.vocabulary import INPUT_FORMATS


def test_every_input_format_has_its_reader():
    """A format offered on the command line is one read_dataset can dispatch: a stream reader,
    Surface Evolver, read by file, or a label image."""
    from grainclass.readers import STREAM_READERS
    from grainclass.readers.images import IMAGE_OPENERS

    assert sorted([*STREAM_READERS, "evolver", *IMAGE_OPENERS]) == sorted(INPUT_FORMATS)


def test_the_package_keeps_its_public_names():
    import grainclass.readers as readers
    from grainclass.readers import sniffing, streams

    assert readers.sniff is sniffing.sniff
    assert readers.not_grains is sniffing.not_grains
    assert readers.SNIFF_BYTES == sniffing.SNIFF_BYTES == 4096
    assert readers.read_once is streams.read_once
    assert readers.done_reading is streams.done_reading
