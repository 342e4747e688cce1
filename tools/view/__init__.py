"""`teleo view`: a live web view of a running launch, a replayed run, or a run record file,
served on 127.0.0.1 (docs/view.md).

One subscriber (tools/view/feeds.py) reads the bus into a model (model.py); the server
(server.py) pushes the newest cycle to the page as server-sent events and answers the page's
requests for past cycles; the page (static/) draws the world and each agent's goals, decision
tree, actions and beliefs panel (why each unsatisfied goal is false: beliefs.py), with a
timeline to step back, a badge saying live, ended or record, and the processes with rates.
"""

from __future__ import annotations

import threading

import click

from bus.config import BusConfig, bus_options
from bus.errors import BusError
from bus.stage import stop_on_signals

DEFAULT_PORT = 8470
CONTROL_TIMEOUT_S = 30.0   # [s] for the world's verdict on a button (a step of one cycle)


@click.command()
@click.argument("record", metavar="[RECORD]", required=False)
@click.option("--run", "run_id", default=None,
              help="Which run to follow (default: the running launch's; with --connect, the "
                   "first run seen, e.g. one `teleo replay` plays).")
@click.option("--port", type=click.IntRange(0, 65535), default=DEFAULT_PORT, show_default=True,
              help="Port on 127.0.0.1 (0: any free port).")
@click.option("--history", type=click.IntRange(min=10), default=5000, show_default=True,
              help="Cycles kept for stepping back.")
@bus_options
def view(record: str | None, run_id: str | None, port: int, history: int,
         bus_config: BusConfig) -> None:
    """Serve a web page showing the running launch live (or RECORD: a run folder, run id or
    .mcap file): the world, each agent's goals and decision tree, processes and rates."""
    from tools.records.run_record import RecordError, locate
    from tools.view.feeds import BusFeed, load_file, scenario_of
    from tools.view.model import ViewModel
    from tools.view.server import ViewServer

    model = ViewModel(run_id, history)
    feed, control = None, None
    try:
        if record is not None:
            load_file(model, locate(record))
        else:
            target = _target(bus_config, run_id)
            model.run = run_id or target.run
            model.programs.from_scenario(*scenario_of(model.run))
            feed = BusFeed(model, target).start()
            control = _control(target, model.run)
        server = ViewServer(model, port, control)
    except RecordError as exc:
        raise click.ClickException(str(exc)) from exc
    except BusError as exc:
        raise click.ClickException(f"cannot follow the bus: {exc}") from exc
    except OSError as exc:
        raise click.ClickException(f"cannot serve on 127.0.0.1:{port}: {exc.strerror}; "
                                   "give another --port (0: any free port)") from exc
    stop = stop_on_signals()
    thread = threading.Thread(target=server.serve_forever, name="teleo-view-http", daemon=True)
    thread.start()
    following = f"run {model.run}" if model.run else "the first run seen"
    click.echo(f"teleo view of {following} ({model.source}) at {server.url}  (Ctrl-C stops)")
    try:
        while not stop.wait(0.5):
            pass
    finally:
        server.closing = True
        server.shutdown()
        server.server_close()
        if feed is not None:
            feed.close()


def _control(target, run: str | None):
    """The timeline's pause, step and resume (tools/runs/control.py), for a launch's own run
    (None for a run `teleo replay` plays onto a launch's router: it has no world to ask)."""
    from tools.runs.control import ask_via

    if not run or target.run != run:
        return None
    return lambda event: ask_via(target.cfg, run, event, CONTROL_TIMEOUT_S, "view-control")


def _target(bus_config: BusConfig, run_id: str | None):
    """The bus to follow: the launch of run `run_id` (or the only one); a run that is no
    launch's (one `teleo replay` plays) on the only running launch's router."""
    from tools.runs.target import TargetError, connect_given, find_target

    try:
        return find_target(bus_config, run=run_id)
    except TargetError:
        if run_id is None or connect_given():
            raise
        try:
            return find_target(bus_config)
        except TargetError:
            pass
        raise


commands = [view]
