"""`teleo event JSON`: inject a world event into a running launch (a fault drill or a new errand)
and report the world's verdict.

The event is asked as a query on teleo/<run>/world/events; the world process applies it at the
start of the next cycle, records its outcome in the run's trace, and answers with that
outcome (docs/bus.md, "World events"). The command prints the verdict and exits 0 when the
world applied the event, 1 when it refused it (with the world's reason) or did not answer.
The event kinds are the world's: in the driving world a pedestrian stepping out, a road
blocked or reopened, a new package (world/driving/injection.py); the blocks and office worlds
have their own (docs/scenarios.md).
"""

from __future__ import annotations

import json

import click

from tools.runs import runfile

VERDICT_TIMEOUT = 10.0  # [s] for the world to apply the event at a cycle boundary and answer


@click.command("event")
@click.argument("event_json", metavar="JSON")
@click.option("--timeout", type=click.FloatRange(min=0.1), default=VERDICT_TIMEOUT,
              show_default=True, help="Seconds to wait for the world's verdict.")
@runfile.run_option
@runfile.quiet_option
def event(event_json: str, timeout: float, run_id: str | None) -> None:
    """Inject a world event into the running launch; print its verdict.

    JSON is the event, e.g. '{"kind": "block", "segment": "S17"}' or
    '{"kind": "pedestrian", "ahead_of": "ME", "dist": 20}', for instance."""
    from bus import keys
    from bus.errors import BusError, NobodyServing, QueryFailed
    from bus.messages import EventReply, WorldEvent
    from bus.node import open_node

    body = read_event(event_json)
    info = runfile.locate(run_id)
    key = keys.world_events(info.run)
    try:
        with open_node(runfile.bus_config(info), info.run, "event-cli") as node:
            reply = node.query(key, WorldEvent(node.envelope(), body), timeout)
    except NobodyServing as exc:
        raise click.ClickException(
            f"run {info.run}: no verdict from the world within {timeout:g} s: it applies events "
            "at the start of a cycle and answers then; is the run stalled or over? "
            "(teleo inspect)") from exc
    except (QueryFailed, BusError) as exc:
        raise click.ClickException(f"run {info.run}: {exc}") from exc
    if not isinstance(reply, EventReply):
        raise click.ClickException(f"run {info.run}: the world answered with a {reply.KIND}")
    if not reply.ok:
        raise click.ClickException(f"run {info.run}: the world refused the event at cycle "
                                   f"{reply.env.cycle}: {reply.reason}")
    click.echo(f"run {info.run}: applied at cycle {reply.env.cycle}: {json.dumps(body)}")


def read_event(text: str) -> dict:
    """The event object in JSON `text`, read within the limits of docs/language.md ("Limits":
    size, depth, numbers, no NaN or Infinity); raises ClickException naming JSON:line:col."""
    from agents.lang import LangError
    from agents.lang.core.limits import MAX_EVENT_CHARS, read_json, shorten

    try:
        body = read_json(text, "JSON", max_chars=MAX_EVENT_CHARS)
    except LangError as exc:
        raise click.ClickException(str(exc)) from None
    if not isinstance(body, dict) or not isinstance(body.get("kind"), str):
        raise click.ClickException(
            f'JSON: expected an object with a "kind", e.g. {{"kind": "block", "segment": "S17"}}'
            f", got {shorten(text, 80)!r}")
    return body


commands = [event]
