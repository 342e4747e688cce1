"""bench/speed/bus_shm.py's probe over real zenoh sessions in two processes: with shared memory
enabled a 15 KB payload put in a shared-memory buffer comes back in shared memory, every time;
with it disabled a put never does (issue 27's measurement of zenoh's shared-memory transport
rests on this; zenoh's default copying of plain puts into shared memory is set up lazily, so
how many of those come back in it depends on timing, and bench/speed/bus_shm.py only counts
them)."""

from __future__ import annotations

import pytest

from bus.shm_probe import round_trips


@pytest.mark.parametrize("shm, enabled, answers_in_shm", [(True, True, 70), (False, False, 0)])
def test_a_payload_comes_back_in_shared_memory_exactly_when_sent_so(shm, enabled,
                                                                     answers_in_shm):
    times, in_shm = round_trips(15_000, 20, shm, enabled)
    assert len(times) == 20 and all(t > 0 for t in times)
    assert in_shm == answers_in_shm   # 50 not timed, 20 timed
