"""Limits that follow the machine's load (bus/load.py; issue 31: at load 20-46 on 2 CPUs
launches failed at the router's fixed 15 s start limit)."""

from __future__ import annotations

from bus.load import MOST, busy, overloaded, scaled


def test_a_limit_is_stretched_by_the_load_per_cpu_and_no_further_than_most():
    assert scaled(15.0, load=(1.0, 2)) == 15.0          # an idle machine: as written
    assert scaled(15.0, load=(20.0, 2)) == 15.0 * min(MOST, 10.0)
    assert scaled(15.0, load=(6.0, 2)) == 45.0
    assert scaled(15.0, load=(46.0, 2)) == 15.0 * MOST
    assert busy((0.3, 16)) == 1.0


def test_a_wait_that_ran_out_on_a_loaded_machine_says_so_in_its_line():
    assert overloaded(15.0, load=(2.0, 2)) == ""
    said = overloaded(120.0, load=(42.0, 2))
    assert said.startswith("; the machine is overloaded (load average 42.0 on 2 CPU(s)): "
                           "waited 120 s")
    assert "\n" not in said
