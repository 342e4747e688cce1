"""`teleo event JSON`: inject a world event into a running launch (a fault drill or a new errand).

The event goes on teleo/<run>/world/events; the world process applies it before the state of
the next cycle it publishes and records the outcome in the run's trace. The event kinds are
the world's (world/injection.py): a pedestrian stepping out, a road blocked or reopened, a
new package.
"""

from __future__ import annotations

import json

import click

from tools import runfile

MATCH_TIMEOUT = 5.0  # [s] to find the world process's subscriber


@click.command("event")
@click.argument("event_json", metavar="JSON")
def event(event_json: str) -> None:
    """Inject JSON, a world event, into the running launch, e.g.
    '{"kind": "block", "segment": "S17"}' or
    '{"kind": "pedestrian", "ahead_of": "ME", "dist": 20}'."""
    from bus import keys
    from bus.config import BusConfig
    from bus.errors import BusError
    from bus.messages import WorldEvent
    from bus.node import open_node

    body = read_event(event_json)
    try:
        info = runfile.find()
    except runfile.NoRunningLaunch as exc:
        raise click.ClickException(str(exc)) from exc
    cfg = BusConfig(mode="client", connect=(info.endpoint,), listen=())
    key = keys.world_events(info.run)
    try:
        with open_node(cfg, info.run, "event-cli") as node:
            node.declare([key])
            if node.wait_matching([key], MATCH_TIMEOUT):
                raise click.ClickException(f"run {info.run}: the world process is not listening "
                                           f"on {key}")
            node.publish(key, WorldEvent(node.envelope(), body))
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc
    click.echo(f"sent to {info.run}: {json.dumps(body)}")


def read_event(text: str) -> dict:
    """The event object in JSON `text`, read within the limits of docs/language.md ("Limits":
    size, depth, numbers, no NaN or Infinity); raises ClickException naming JSON:line:col."""
    from agents.lang import LangError
    from agents.lang.limits import MAX_EVENT_CHARS, read_json, shorten

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
