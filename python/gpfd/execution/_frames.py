"""The wire of gpfd's worker processes (gpfd.workers, gpfd.execution._worker): frames of an 8-byte
big-endian length followed by that many bytes of cloudpickle, on a pipe's file descriptor."""

from __future__ import annotations

import os
import struct
from typing import Any

import cloudpickle

_HEADER = struct.Struct(">Q")


def send(fd: int, message: Any) -> None:
    """Writes `message` (cloudpickle) as one frame; OSError (BrokenPipeError) when the reader is
    gone."""
    send_bytes(fd, cloudpickle.dumps(message))


def send_bytes(fd: int, payload: bytes) -> None:
    """Writes `payload` as one frame."""
    view = memoryview(_HEADER.pack(len(payload)) + payload)
    while view:
        view = view[os.write(fd, view) :]


def _read_exactly(fd: int, size: int) -> bytes | None:
    """`size` bytes, or None at the end of the pipe before any of them; EOFError within them."""
    chunks, left = [], size
    while left:
        chunk = os.read(fd, min(left, 1 << 20))
        if not chunk:
            if left == size:
                return None
            raise EOFError(f"a frame ended after {size - left} of its {size} bytes")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def receive(fd: int) -> Any:
    """The next frame's message (cloudpickle); EOFError at the end of the pipe."""
    return cloudpickle.loads(receive_bytes(fd))


def receive_bytes(fd: int) -> bytes:
    """The next frame's bytes; EOFError at the end of the pipe."""
    header = _read_exactly(fd, _HEADER.size)
    if header is None:
        raise EOFError("the pipe is closed")
    (size,) = _HEADER.unpack(header)
    payload = _read_exactly(fd, size) if size else b""
    if payload is None:
        raise EOFError("the pipe closed within a frame")
    return payload
