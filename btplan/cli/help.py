"""Help text that reads like a man page: metavars say what goes there, no Python types.

typer shows a Python type beside each parameter (`<str>`, `<bool>`, `<list[str]>`) and
wraps required arguments in braces in the usage line (`{DOMAIN} [[PROBLEM]]`). Users
of git or ripgrep expect `DOMAIN [PROBLEM]` and `-o, --output FILE`. The group class
below swaps every parameter of every command for a variant that shows its metavar (or
nothing, for a flag), once, when the app is built.

The same variants convert well-formed values of plain types (str, bool, int, float, an
Enum, a list of str) themselves. typer converts every value with a pydantic TypeAdapter,
and importing pydantic and building the adapters took longer than planning a small
problem; anything unusual (a range, a malformed number, another type) still goes to
typer's own conversion, so its checks and messages are unchanged.
"""

from __future__ import annotations

from collections.abc import Callable
from enum import Enum
from typing import Any, get_args, get_origin

from typer.core import TyperArgument, TyperGroup, TyperOption


class _Plain:
    """Converts a value of a plain type; anything else goes to typer's conversion."""

    def __init__(self, convert: Callable[[Any], Any], typer_param: Callable[[], Any]) -> None:
        self.convert = convert
        self.typer_param = typer_param

    def coerce(self, value: Any, param: Any, ctx: Any) -> Any:
        if value is None:
            return () if param.multiple or param.nargs == -1 else None
        try:
            return self.convert(value)
        except (TypeError, ValueError):  # typer says what is wrong, as it always does
            return self.typer_param().coerce(value, param=param, ctx=ctx)


def _converter(annotation: Any, info: Any) -> Callable[[Any], Any] | None:
    """How to convert a well-formed value of `annotation`, or None to leave it to typer."""
    if info.parser is not None or info.min is not None or info.max is not None:
        return None
    if annotation in (str, bool):
        return _exactly(annotation)
    if annotation in (int, float):
        return lambda value: value if type(value) is annotation else annotation(_text(value))
    if isinstance(annotation, type) and issubclass(annotation, Enum) and info.case_sensitive:
        return annotation
    if get_origin(annotation) is list and get_args(annotation) == (str,):
        return lambda values: [_exactly(str)(v) for v in values]
    return None


def _exactly(kind: type) -> Callable[[Any], Any]:
    def same(value: Any) -> Any:
        if type(value) is not kind:
            raise TypeError(value)
        return value

    return same


def _text(value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError(value)
    return value


def _runtime_param(param: Any, typer_param: Callable[[], Any]) -> Any:
    """What converts `param`'s values: `_Plain` for plain types, else typer's own."""
    descriptor = getattr(param, "type_descriptor", None)
    if descriptor is None or descriptor.file_annotation is not None:
        return typer_param()
    convert = _converter(descriptor.annotation, descriptor.parameter_info)
    return typer_param() if convert is None else _Plain(convert, typer_param)


class Argument(TyperArgument):
    """An argument shown by its metavar alone: `DOMAIN`, `[PROBLEM]`, `FILE...`."""

    def get_runtime_param(self) -> Any:
        """The converter of this argument's values: the plain one for plain types, so that
        pydantic is not imported (module docstring), else typer's."""
        return _runtime_param(self, super().get_runtime_param)

    def display_type_rich(self, ctx: Any) -> str | None:
        """No type beside an argument in the help: its metavar already says what goes there."""
        return None

    def get_usage_pieces(self, ctx: Any) -> list[str]:
        """The argument in the usage line as `NAME`, `[NAME]` when optional, `NAME...` for
        several, instead of typer's braces."""
        name = self.metavar or (self.name or "").upper()
        if self.nargs != 1:
            name += "..."
        return [name if self.required else f"[{name}]"]


class Option(TyperOption):
    """An option shown with its metavar (`--seed N`), a choice list, or nothing (a flag)."""

    def get_runtime_param(self) -> Any:
        """The converter of this option's values: the plain one for plain types, so that pydantic
        is not imported (module docstring), else typer's."""
        return _runtime_param(self, super().get_runtime_param)

    def display_type_rich(self, ctx: Any) -> str | None:
        """What follows the option's names in the help: its metavar, nothing for a flag, else
        typer's text without the angle brackets of a Python type (an Enum's choices)."""
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
        """The commands in the order they are declared, not sorted by name as click does."""
        return list(self.commands)
