"""Bus recordings: a msgpack stream file, first a header map
`{"teleo_record": 1, "run": RUN, "start_ns": NS}`, then one `[key, t_ns, payload]` array per
sample (raw payload bytes as received, receive time [ns since the epoch])."""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass
from typing import BinaryIO

import msgpack

from bus.errors import CodecError

FORMAT_VERSION = 1


@dataclass(frozen=True)
class Sample:
    key: str
    t_ns: int
    payload: bytes


class Recorder:
    """Appends samples to an open binary file."""

    def __init__(self, out: BinaryIO, run: str) -> None:
        self.out = out
        self.count = 0
        self._packer = msgpack.Packer(use_bin_type=True)
        out.write(self._packer.pack({"teleo_record": FORMAT_VERSION, "run": run,
                                     "start_ns": time.time_ns()}))

    def write(self, key: str, t_ns: int, payload: bytes) -> None:
        self.out.write(self._packer.pack([key, t_ns, payload]))
        self.count += 1


def read_recording(path: str) -> tuple[dict, Iterator[Sample]]:
    """The header and the samples of a recording; raises CodecError if it is not one."""
    f = open(path, "rb")  # closed by samples() or on error below
    unpacker = msgpack.Unpacker(f, raw=False, strict_map_key=True)
    try:
        header = next(unpacker)
    except (StopIteration, ValueError, msgpack.UnpackException) as exc:
        f.close()
        raise CodecError(path, f"not a teleo recording: {exc}") from exc
    if not isinstance(header, dict) or header.get("teleo_record") != FORMAT_VERSION:
        f.close()
        raise CodecError(path, f"not a teleo recording (version {FORMAT_VERSION}): {header!r:.80}")

    def samples() -> Iterator[Sample]:
        with f:
            for item in unpacker:
                if (isinstance(item, list) and len(item) == 3 and isinstance(item[0], str)
                        and isinstance(item[2], bytes)):
                    yield Sample(item[0], int(item[1]), item[2])
                else:
                    raise CodecError(path, f"malformed record {item!r:.80}")

    return header, samples()
