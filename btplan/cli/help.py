"""Help text that reads like a man page: metavars say what goes there, no Python types.

typer shows a Python type beside each parameter (`<str>`, `<bool>`, `<list[str]>`) and
wraps required arguments in braces in the usage line (`{DOMAIN} [[PROBLEM]]`). Users
of git or ripgrep expect `DOMAIN [PROBLEM]` and `-o, --output FILE`. The group class
below swaps every parameter of every command for a variant that shows its metavar (or
nothing, for a flag), once, when the app is built.
"""

from __future__ import annotations

from typing import Any

from typer.core import TyperArgument, TyperGroup, TyperOption


class Argument(TyperArgument):
    """An argument shown by its metavar alone: `DOMAIN`, `[PROBLEM]`, `FILE...`."""

    def display_type_rich(self, ctx: Any) -> str | None:
        return None

    def get_usage_pieces(self, ctx: Any) -> list[str]:
        name = self.metavar or (self.name or "").upper()
        if self.nargs != 1:
            name += "..."
        return [name if self.required else f"[{name}]"]


class Option(TyperOption):
    """An option shown with its metavar (`--seed N`), a choice list, or nothing (a flag)."""

    def display_type_rich(self, ctx: Any) -> str | None:
        if self.metavar is not None:
            return self.metavar
        if self.is_flag:
            return None
        shown = super().display_type_rich(ctx) or ""
        return shown.strip("<>") or None


def _plain_param(param: Any) -> Any:
    if type(param) is TyperArgument:
        param.__class__ = Argument
    elif type(param) is TyperOption:
        param.__class__ = Option
    return param


def plain(command: Any) -> None:
    """Give `command`'s parameters (and its subcommands', for a group) plain help.

    Some parameters are added after the command is built (-h/--help, the completion
    options), so the method that lists them is wrapped rather than the list changed.
    """
    listed = command.get_params
    command.get_params = lambda ctx: [_plain_param(p) for p in listed(ctx)]
    for sub in getattr(command, "commands", {}).values():
        plain(sub)


class Group(TyperGroup):
    """The `btplan` group: commands in the order they are declared, with plain help."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        plain(self)

    def list_commands(self, ctx: Any) -> list[str]:
        return list(self.commands)
