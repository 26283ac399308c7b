"""Standard input and FIFOs read ahead (:class:`grainclass.pipes.ReadAhead`): the writer goes
on while grainclass starts up, and the reader gets exactly the bytes written, in order."""

import os
import random
import subprocess
import sys
import threading

import pytest

from grainclass.pipes import (
    PIPE_BYTES,
    ReadAhead,
    read_ahead,
    read_ahead_path,
    reading_ahead,
    take_read_ahead,
)

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX pipes")


def _writer(fd: int, data: bytes, pieces: random.Random) -> threading.Thread:
    """A thread writing ``data`` into ``fd`` in pieces of random sizes, then closing it."""

    def write() -> None:
        with os.fdopen(fd, "wb", buffering=0) as out:
            at = 0
            while at < len(data):
                size = pieces.randint(1, 70_000)
                out.write(data[at : at + size])
                at += size

    thread = threading.Thread(target=write)
    thread.start()
    return thread


def _read_all(stream: ReadAhead, pieces: random.Random) -> bytes:
    got = bytearray()
    while True:
        buffer = bytearray(pieces.randint(1, 3 * PIPE_BYTES))
        n = stream.readinto(buffer)
        if not n:
            return bytes(got)
        got += buffer[:n]


@pytest.mark.parametrize("limit", [1, 5_000, 1 << 28])
def test_the_reader_gets_every_byte_in_order(limit):
    # Any limit, down to one byte ahead: a read-ahead that holds what it may not lose bytes.
    pieces = random.Random(limit)
    data = random.Random(7).randbytes(3 * PIPE_BYTES + 12_345)
    read_end, write_end = os.pipe()
    writer = _writer(write_end, data, pieces)
    stream = ReadAhead(read_end, gather=False, limit=limit)
    assert _read_all(stream, pieces) == data
    assert stream.readinto(bytearray(10)) == 0  # at the end it stays there
    writer.join()
    os.close(read_end)


def test_the_writer_is_not_kept_waiting_before_the_first_read():
    # Three times what a pipe holds is written and the pipe closed before anything is read,
    # as plantri goes on writing while grainclass imports its libraries.
    data = bytes(range(256)) * (3 * PIPE_BYTES // 256)
    read_end, write_end = os.pipe()
    stream = ReadAhead(read_end, gather=True)
    writer = _writer(write_end, data, random.Random(1))
    writer.join(timeout=60)
    assert not writer.is_alive()
    assert _read_all(stream, random.Random(2)) == data
    os.close(read_end)


def test_the_read_ahead_stops_at_its_limit():
    # Past the limit the thread reads no more: the pipe fills up and the writer waits.
    read_end, write_end = os.pipe()
    stream = ReadAhead(read_end, gather=False, limit=PIPE_BYTES)
    writer = _writer(write_end, bytes(20 * PIPE_BYTES), random.Random(3))
    writer.join(timeout=2)
    assert writer.is_alive()
    assert len(_read_all(stream, random.Random(4))) == 20 * PIPE_BYTES
    writer.join()
    os.close(read_end)


def test_a_read_error_reaches_the_reader(tmp_path):
    fd = os.open(tmp_path, os.O_RDONLY)  # reading a folder fails: EISDIR
    try:
        with pytest.raises(IsADirectoryError):
            ReadAhead(fd, gather=False).readinto(bytearray(10))
    finally:
        os.close(fd)


def test_only_a_pipe_is_read_ahead(tmp_path):
    path = tmp_path / "file"
    path.write_bytes(b"4 2 3 4")
    with path.open("rb") as regular:
        assert read_ahead(regular) is None
        assert reading_ahead(regular) is None
    read_end, write_end = os.pipe()
    with os.fdopen(read_end, "rb") as pipe:
        os.close(write_end)
        ahead = read_ahead(pipe)
        assert isinstance(ahead, ReadAhead)
        assert read_ahead(pipe) is ahead  # started once
        assert reading_ahead(pipe) is ahead


def test_standard_input_read_ahead_summarizes_as_the_file(tmp_path, plantri):
    # The command line reads a pipe ahead of use (cli.startup.read_ahead): what it counts is
    # what the same records give from a file.
    path = tmp_path / "p11.pc"
    subprocess.run([plantri, "11", str(path)], check=True, capture_output=True)
    command = [sys.executable, "-m", "grainclass", "summarize", "--format", "csv", "-q"]
    from_file = subprocess.run([*command, str(path)], check=True, capture_output=True)
    with path.open("rb") as data:
        piped = subprocess.Popen([*command, "-"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        out, _ = piped.communicate(data.read())
    assert piped.returncode == 0
    assert out == from_file.stdout
    assert b"1249" in out  # plantri 11's triangulations, Table I


def test_a_fifo_is_opened_by_the_read_ahead_and_read_whole(tmp_path):
    """A FIFO's reader opens it, which waits for a writer: that wait is the thread's, not the
    command's, and a writer that comes late is read from its first byte, in order."""
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    stream = ReadAhead(str(fifo))  # no writer yet: returns at once
    data = random.Random(8).randbytes(3 * PIPE_BYTES + 999)
    writer = _writer(os.open(fifo, os.O_WRONLY), data, random.Random(9))
    writer.join(timeout=60)
    assert not writer.is_alive()  # three pipes' worth written before the first read
    assert _read_all(stream, random.Random(10)) == data
    stream.close()


def test_a_fifo_closed_under_its_thread_is_left_to_the_thread(tmp_path, monkeypatch):
    """close() while the thread is about to read the FIFO: the FIFO's descriptor stays the
    thread's until its read is done, so a pipe opened meanwhile cannot get that descriptor and
    lose its bytes to the read; the thread closes the FIFO when it ends."""
    about_to_read, go_on = threading.Event(), threading.Event()
    read = os.read
    paused: list[threading.Thread] = []  # this stream's thread, not another test's
    thread_read: list[bytes | OSError] = []

    def read_after_a_pause(fd: int, size: int) -> bytes:
        if threading.current_thread() not in paused:
            return read(fd, size)
        about_to_read.set()
        go_on.wait(timeout=30)
        try:
            thread_read.append(read(fd, size))
        except OSError as exc:
            thread_read.append(exc)
            raise
        return thread_read[-1]

    monkeypatch.setattr(os, "read", read_after_a_pause)
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    before = set(threading.enumerate())
    stream = ReadAhead(str(fifo))
    (thread,) = set(threading.enumerate()) - before
    paused.append(thread)
    writer = os.open(fifo, os.O_WRONLY)  # waits for the thread to open the FIFO
    assert about_to_read.wait(timeout=30)
    os.write(writer, b"fifo")
    stream.close()
    other_read_end, other_write_end = os.pipe()
    os.write(other_write_end, b"theirs")
    go_on.set()
    thread.join(timeout=30)
    assert not thread.is_alive()
    assert thread_read == [b"fifo"]
    os.set_blocking(other_read_end, False)
    assert read(other_read_end, 100) == b"theirs"
    with pytest.raises(BrokenPipeError):  # the thread closed the FIFO's reading end
        os.write(writer, b"more")
    for fd in (writer, other_read_end, other_write_end):
        os.close(fd)


def test_a_fifo_that_cannot_be_opened_fails_the_first_read(tmp_path):
    with pytest.raises(IsADirectoryError):
        ReadAhead(str(tmp_path)).readinto(bytearray(10))


def test_only_a_fifo_path_is_read_ahead_and_handed_over_once(tmp_path):
    path = tmp_path / "file"
    path.write_bytes(b"4 2 3 4")
    assert read_ahead_path(str(path)) is None
    assert read_ahead_path(str(tmp_path / "missing")) is None
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    ahead = read_ahead_path(str(fifo))
    assert isinstance(ahead, ReadAhead)
    assert read_ahead_path(str(fifo)) is ahead  # started once
    assert take_read_ahead(str(fifo)) is ahead
    assert take_read_ahead(str(fifo)) is None  # its reader has it
    os.close(os.open(fifo, os.O_WRONLY))  # a writer that writes nothing: the thread ends
    assert ahead.readinto(bytearray(10)) == 0
    ahead.close()


def test_a_process_substitution_summarizes_as_the_file(tmp_path, plantri):
    # <(plantri 11): the command line reads its first input ahead when it is a FIFO.
    path = tmp_path / "p11.pc"
    subprocess.run([plantri, "11", str(path)], check=True, capture_output=True)
    command = [sys.executable, "-m", "grainclass", "summarize", "--format", "csv", "-q"]
    from_file = subprocess.run([*command, str(path)], check=True, capture_output=True)
    substituted = subprocess.run(
        ["bash", "-c", f'"$0" "$@" <(cat "{path}")', *command],
        check=True,
        capture_output=True,
    )
    assert substituted.stdout == from_file.stdout
    assert b"1249" in substituted.stdout  # plantri 11's triangulations, Table I
