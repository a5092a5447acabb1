"""MkDocs hook: the command-line reference, generated from the typer app itself.

The page docs/reference/commands.md holds the marker `<!-- commands -->`; at build time
it is replaced by every command and subcommand with its usage line, its help and a table
of its options (names, value, default, help), read from the app that `btplan` runs, so
the reference cannot fall behind the code.
"""

from __future__ import annotations

from typing import Any

MARKER = "<!-- commands -->"


def on_page_markdown(markdown: str, page: Any, **_: Any) -> str:
    if MARKER not in markdown:
        return markdown
    import typer.main

    from btplan.cli import _the_app

    root = typer.main.get_command(_the_app())
    return markdown.replace(MARKER, "\n".join(_commands(root, "btplan")))


def _commands(group: Any, prefix: str) -> list[str]:
    import click

    out: list[str] = []
    for name in sorted(group.commands):
        command = group.commands[name]
        if command.hidden:
            continue
        path = f"{prefix} {name}"
        if isinstance(command, click.Group) or hasattr(command, "commands"):
            out.extend(_commands(command, path))
            continue
        context = click.Context(command, info_name=path)
        out += [f"## `{path}`", "", "```", command.get_usage(context).replace("Usage: ", ""),
                "```", "", _clean(command.help or ""), ""]
        rows = [_row(p) for p in command.params
                if p.param_type_name == "option" and not p.hidden]
        if rows:
            out += ["| option | value | default | what it does |", "| --- | --- | --- | --- |",
                    *rows, ""]
    return out


def _row(option: Any) -> str:
    names = ", ".join(f"`{n}`" for n in [*option.opts, *getattr(option, "secondary_opts", [])])
    kind = getattr(option, "type", None)
    choices = getattr(kind, "choices", None)
    shape = getattr(option, "metavar", None) or (
        "|".join(str(c) for c in choices) if choices else getattr(kind, "name", "value").upper())
    value = "" if getattr(option, "is_flag", False) else f"`{shape}`"
    default = getattr(option, "default", None)
    default = getattr(default, "value", default)  # an enum's member: its value
    shown = "" if default in (None, (), [], False) or callable(default) else f"`{default}`"
    return f"| {names} | {value} | {shown} | {_clean(getattr(option, 'help', None) or '')} |"


def _clean(text: str) -> str:
    """Help text for a table cell or a paragraph: one line, pipes escaped."""
    return " ".join(text.split()).replace("|", "\\|")
