"""`teleo worlds`: every world teleo can run, as found among the installed packages' entry
points (group ``teleo.worlds``, world/registry.py): its name, the package and version that
provide it, its one-line summary, and for a world that failed to load, why (one line, no
traceback). Listing imports each world, so a broken one is found here rather than at a run's
start; the others are listed and run as ever.
"""

from __future__ import annotations

import json

import click


@click.command("worlds")
@click.option("--json", "as_json", is_flag=True,
              help='One JSON object: {"worlds": [{name, package, version, target, summary, '
                   'error}]}.')
def worlds(as_json: bool) -> None:
    """List the worlds found (teleo's own and installed plug-ins), and why any failed."""
    from world.domain import Domain
    from world.registry import survey

    rows = survey(Domain)
    if as_json:
        click.echo(json.dumps({"worlds": [
            {"name": f.entry.name, "package": f.entry.dist, "version": f.entry.version,
             "target": f.entry.target, "summary": f.summary, "error": f.error}
            for f in rows]}))
        return
    if not rows:
        click.echo("no worlds found (no package registers a `teleo.worlds` entry point)")
        return
    sources = [f"{f.entry.dist} {f.entry.version}".strip() or "?" for f in rows]
    width, wide = max(len(f.entry.name) for f in rows), max(len(s) for s in sources)
    for f, source in zip(rows, sources, strict=True):
        text = f"FAILED: {f.error}" if f.error else f.summary
        click.echo(f"{f.entry.name:<{width}}  {source:<{wide}}  {text}")
    failed = sum(1 for f in rows if f.error)
    if failed:
        click.echo(f"{failed} world(s) failed to load; the others run as ever")


commands = [worlds]
