"""Plain record classes, as `dataclasses.dataclass` makes them, without its start-up cost.

`btplan plan` is measured as a whole process beside other planners, and on a small
problem it spends more time starting than planning. `dataclasses` writes every method
of every class as source text and compiles it when the module is imported (about 1 ms
a frozen class, 40 classes on the planning path), and it imports `inspect` to do so.
`record` builds the same kind of class from a few shared methods instead, which the
interpreter loads compiled: the same fields, defaults and `field(default_factory=...)`,
the same `__init__` (positional or keyword-only), `__repr__`, `__eq__`, `__hash__`,
frozen and slotted classes, and `replace`. `dataclasses.fields`, `replace` and `asdict`
take records too. `tests/test_records.py` checks the two agree.

This module imports nothing from btplan: every layer may build its records with it.
"""

from __future__ import annotations

from collections.abc import Callable
from operator import attrgetter

TYPE_CHECKING = False
if TYPE_CHECKING:  # `typing` is left unimported to run: it took 4 ms of a small `btplan plan`
    from typing import Any, TypeVar, overload
    from typing import dataclass_transform as dataclass_transform

    T = TypeVar("T")
else:
    def overload(function: Any) -> Any:
        return function

    def dataclass_transform(**_: Any) -> Any:
        """Read by type checkers as `typing.dataclass_transform`; nothing at run time."""
        return overload

_MISSING: Any = object()
_set = object.__setattr__


class Field:
    """A field's default made by a factory on every construction: `field(default_factory=list)`."""

    __slots__ = ("default_factory",)

    def __init__(self, default_factory: Callable[[], Any]) -> None:
        self.default_factory = default_factory


def field(*, default_factory: Callable[[], T]) -> T:
    """A default built afresh for every record, as `dataclasses.field(default_factory=...)`."""
    made: T = Field(default_factory)  # type: ignore[assignment]  # as dataclasses types it
    return made


@overload
def record(cls: type[T], /) -> type[T]:
    """`@record` bare: the class made a record with every option off."""


@overload
def record(*, frozen: bool = False, slots: bool = False,
           kw_only: bool = False) -> Callable[[type[T]], type[T]]:
    """`@record(frozen=..., slots=..., kw_only=...)`: a decorator making records with
    those options, as `dataclass(...)` takes them."""


@dataclass_transform(field_specifiers=(field,))
def record(cls: type[T] | None = None, /, *, frozen: bool = False, slots: bool = False,
           kw_only: bool = False) -> Any:
    """The class made a record of the fields its annotations declare, in their order."""

    def wrap(target: type[T]) -> type[T]:
        return build(target, frozen=frozen, slots=slots, kw_only=kw_only)

    return wrap if cls is None else wrap(cls)


def build(cls: type[T], *, frozen: bool, slots: bool, kw_only: bool) -> type[T]:
    """What `record` does; the model's base class calls it for every subclass."""
    names: list[str] = []
    defaults: dict[str, Any] = {}
    for base in reversed(cls.__mro__[1:]):
        inherited = base.__dict__.get("__record_fields__")
        if inherited is not None:
            names.extend(n for n in inherited if n not in names)
            defaults.update(base.__dict__["__record_defaults__"])
    for name, annotation in cls.__dict__.get("__annotations__", {}).items():
        if str(annotation).startswith(("ClassVar", "typing.ClassVar")):
            continue
        if name not in names:
            names.append(name)
        if name in cls.__dict__:
            defaults[name] = cls.__dict__[name]
        else:
            defaults.pop(name, None)
    if not kw_only:
        for before, after in zip(names, names[1:]):
            if before in defaults and after not in defaults:
                raise TypeError(f"non-default argument {after!r} follows default argument")
    namespace = dict(cls.__dict__)
    for name, default in defaults.items():
        if isinstance(default, Field) or (slots and name in namespace):
            namespace.pop(name, None)
    namespace.update(
        __record_fields__=tuple(names), __record_defaults__=defaults,
        __record_kw_only__=kw_only, __match_args__=() if kw_only else tuple(names),
        __record_values__=_getter(names), __record_required__=frozenset(
            n for n in names if n not in defaults),
        __record_start__={n: defaults.get(n, _MISSING) for n in names},
        __record_least__=sum(1 for n in names if n not in defaults),
        __record_post__=getattr(cls, "__post_init__", None),
        __record_factories__=tuple((n, d.default_factory) for n, d in defaults.items()
                                   if isinstance(d, Field)),
        __record_in_dict__=frozen and not slots and not any(
            isinstance(d, Field) for d in defaults.values()),
        __init__=_init, __repr__=_repr, __eq__=_eq, __dataclass_fields__=_DataclassFields())
    if "__hash__" not in cls.__dict__ or namespace["__hash__"] is None:
        namespace["__hash__"] = _hash if frozen else None
    if frozen:
        namespace.update(__setattr__=_frozen_setattr, __delattr__=_frozen_delattr)
    if slots:
        namespace.pop("__dict__", None)
        namespace.pop("__weakref__", None)
        namespace["__slots__"] = tuple(names)
        if frozen:  # unpickling and copying set slots through __setattr__ otherwise
            namespace.update(__getstate__=_getstate, __setstate__=_setstate)
        made: type[T] = type(cls)(cls.__name__, cls.__bases__, namespace)  # type: ignore[misc]
        made.__qualname__ = cls.__qualname__
        return made
    for name, value in namespace.items():
        if name not in cls.__dict__ or cls.__dict__[name] is not value:
            type.__setattr__(cls, name, value)
    for name in [n for n, d in defaults.items() if isinstance(d, Field) and n in cls.__dict__]:
        type.__delattr__(cls, name)  # as dataclasses leaves no class attribute for a factory
    return cls


HOT = 2048
"""Records a class makes with the shared `__init__` before it gets one of its own.
One written for the class takes 0.2 us a record against 1.3 (a report of two fields
given), but compiling it costs about 0.03 ms, and the first compile of a process about
1 ms more (a `btplan plan` of a small problem took 1-2.5 ms longer with this at 256).
At this count a class has already spent some 3 ms constructing, and one that made this
many makes more: a goal set or a sweep gets it within its first calls, while of the
small IPC problems only mystery p09 (2,408 grounded actions, 0.24 s) compiles one."""

_made: dict[type, int] = {}


def _init(self: Any, *args: Any, **kwargs: Any) -> None:
    """The generated `__init__` of `dataclasses`, for every record alike.

    A class that makes HOT records gets an `__init__` of its own then (`_own_init`):
    the few classes a planning call or a tick makes by the dozen (reports, expansions,
    options copied with a change) are made four to seven times faster, and a process
    that makes a few of each compiles nothing."""
    cls = type(self)
    made = _made.get(cls, 0) + 1
    _made[cls] = made
    if made == HOT and cls.__dict__.get("__init__") is _init:
        type.__setattr__(cls, "__init__", _own_init(cls))
    names: tuple[str, ...] = cls.__record_fields__
    if not kwargs and len(args) == len(names) and not cls.__record_kw_only__:
        for name, value in zip(names, args):  # every field given in order: the common case
            _set(self, name, value)
    elif (not kwargs and cls.__record_least__ <= len(args) < len(names)
          and not cls.__record_kw_only__):
        for name, value in zip(names, args):  # the first fields, the rest left to defaults
            _set(self, name, value)
        start = cls.__record_start__
        for name in names[len(args):]:
            value = start[name]
            _set(self, name, value.default_factory() if isinstance(value, Field) else value)
    elif not args and cls.__record_in_dict__ and cls.__record_required__ <= kwargs.keys():
        values = dict(cls.__record_start__)  # a frozen model by keyword: set in one go
        values.update(kwargs)
        if len(values) != len(names):
            _bind(self, cls, names, args, kwargs)  # an unknown keyword: refused there
        self.__dict__.update(values)
    elif not args and cls.__record_required__ <= kwargs.keys():
        values = dict(cls.__record_start__)  # by keyword: the defaults, then what is given
        values.update(kwargs)
        if len(values) != len(names):
            _bind(self, cls, names, args, kwargs)  # an unknown keyword: refused there
        for name, made in cls.__record_factories__:
            if name not in kwargs:
                values[name] = made()
        for name, value in values.items():
            _set(self, name, value)
    else:
        _bind(self, cls, names, args, kwargs)
    post = cls.__record_post__  # looked up when the class was made: a subclass is made too
    if post is not None:
        post(self)


_init.__record_init__ = True  # type: ignore[attr-defined]  # see `replace`


def _own_init(cls: type) -> Callable[..., None]:
    """An `__init__` written for `cls`, as `dataclasses` writes one: its fields as
    parameters (keyword-only, with `kw_only`), defaults and factories as given, each
    field set in order (through `object.__setattr__` where the class guards its own),
    then `__post_init__`."""
    names: tuple[str, ...] = cls.__record_fields__  # type: ignore[attr-defined]
    start: dict[str, Any] = cls.__record_start__  # type: ignore[attr-defined]
    scope: dict[str, Any] = {"_MISSING": _MISSING, "_set": _set,
                             "_post": cls.__record_post__}  # type: ignore[attr-defined]
    guarded = cls.__setattr__ is not object.__setattr__  # type: ignore[comparison-overlap]
    direct = "__slots__" not in cls.__dict__ and not guarded
    parameters, body = [], []
    for number, name in enumerate(names):
        value = start[name]
        if value is _MISSING:
            parameters.append(name)
        elif isinstance(value, Field):
            scope[f"_f{number}"] = value.default_factory
            parameters.append(f"{name}=_MISSING")
            body.append(f"    if {name} is _MISSING: {name} = _f{number}()")
        else:
            scope[f"_d{number}"] = value
            parameters.append(f"{name}=_d{number}")
        body.append(f"    self.{name} = {name}" if direct else f"    _set(self, {name!r}, {name})")
    if cls.__record_post__ is not None:  # type: ignore[attr-defined]
        body.append("    _post(self)")
    star = ["*"] if cls.__record_kw_only__ and names else []  # type: ignore[attr-defined]
    signature = ", ".join(["self", *star, *parameters])
    source = f"def __init__({signature}) -> None:\n" + "\n".join(body or ["    pass"])
    code = compile(source, f"<record {cls.__qualname__}>", "exec")
    exec(code, scope)  # noqa: S102 (our own text, from the class's field names)
    made: Callable[..., None] = scope["__init__"]
    made.__qualname__ = f"{cls.__qualname__}.__init__"
    made.__record_init__ = True  # type: ignore[attr-defined]
    return made


def _bind(self: Any, cls: type, names: tuple[str, ...], args: tuple[Any, ...],
          kwargs: dict[str, Any]) -> None:
    """Fields given by keyword or left to their defaults, refused as Python refuses them."""
    if args:
        kw_only: bool = cls.__record_kw_only__  # type: ignore[attr-defined]
        if kw_only or len(args) > len(names):
            most = 1 + (0 if kw_only else len(names))
            raise TypeError(f"{cls.__qualname__}.__init__() takes {most} positional arguments"
                            f" but {1 + len(args)} were given")
        for name, value in zip(names, args):
            if name in kwargs:
                raise TypeError(f"{cls.__qualname__}.__init__() got multiple values for "
                                f"argument {name!r}")
            kwargs[name] = value
    defaults: dict[str, Any] = cls.__record_defaults__  # type: ignore[attr-defined]
    for name in names:
        value = kwargs.pop(name, _MISSING)
        if value is _MISSING:
            value = defaults.get(name, _MISSING)
            if value is _MISSING:
                raise TypeError(f"{cls.__qualname__}.__init__() missing 1 required argument: "
                                f"{name!r}")
            if isinstance(value, Field):
                value = value.default_factory()
        _set(self, name, value)
    if kwargs:
        raise TypeError(f"{cls.__qualname__}.__init__() got an unexpected keyword argument "
                        f"{next(iter(kwargs))!r}")


def _values(self: Any) -> tuple[Any, ...]:
    values: tuple[Any, ...] = type(self).__record_values__(self)
    return values


def field_values(obj: Any, /) -> tuple[Any, ...]:
    """The record's fields' values in order, as they are (`dataclasses.astuple` copies
    them, deeply): what it compares and hashes by."""
    return _values(obj)


def _getter(names: list[str]) -> Callable[[Any], tuple[Any, ...]]:
    """The fields' values as a tuple, read in C: what equality and hashing compare."""
    if len(names) >= 2:
        return attrgetter(*names)
    if names:
        only = attrgetter(names[0])
        return lambda record: (only(record),)
    return lambda record: ()


_repr_running: set[tuple[int, int]] = set()


def _repr(self: Any) -> str:
    key = (id(self), id(type(self)))
    if key in _repr_running:  # a record that holds itself, as reprlib.recursive_repr has it
        return "..."
    _repr_running.add(key)
    try:
        inner = ", ".join(f"{n}={getattr(self, n)!r}" for n in self.__record_fields__)
    finally:
        _repr_running.discard(key)
    return f"{type(self).__qualname__}({inner})"


def _eq(self: Any, other: Any) -> Any:
    if other.__class__ is self.__class__:
        values = self.__class__.__record_values__
        return values(self) == values(other)
    return NotImplemented


def _hash(self: Any) -> int:
    return hash(type(self).__record_values__(self))


def _frozen_setattr(self: Any, name: str, value: Any) -> None:
    from dataclasses import FrozenInstanceError

    raise FrozenInstanceError(f"cannot assign to field {name!r}")


def _frozen_delattr(self: Any, name: str) -> None:
    from dataclasses import FrozenInstanceError

    raise FrozenInstanceError(f"cannot delete field {name!r}")


def _getstate(self: Any) -> list[Any]:
    return list(_values(self))


def _setstate(self: Any, state: list[Any]) -> None:
    for name, value in zip(self.__record_fields__, state):
        _set(self, name, value)


def replace(obj: T, /, **changes: Any) -> T:
    """A copy of the record with some fields changed, as `dataclasses.replace`.

    Every field is passed in order, positionally, where the record's own `__init__`
    takes them so: the quickest way through it (a planning call makes a few dozen
    copies)."""
    cls = type(obj)
    if cls.__record_kw_only__ or not getattr(  # type: ignore[attr-defined]
            cls.__init__, "__record_init__", False):
        for name in cls.__record_fields__:  # type: ignore[attr-defined]
            if name not in changes:
                changes[name] = getattr(obj, name)
        return cls(**changes)
    values = [changes.pop(name) if name in changes else getattr(obj, name)
              for name in cls.__record_fields__]  # type: ignore[attr-defined]
    return cls(*values, **changes)  # a change left over is no field: __init__ refuses it


class _DataclassFields:
    """`__dataclass_fields__`, made on first use, so that `dataclasses.fields`, `replace`,
    `asdict` and `is_dataclass` take records as the dataclasses they stand for."""

    def __get__(self, instance: Any, owner: type) -> dict[str, Any]:
        import dataclasses

        made: dict[str, Any] = {}
        defaults = owner.__record_defaults__  # type: ignore[attr-defined]
        kw_only = owner.__record_kw_only__  # type: ignore[attr-defined]
        for name in owner.__record_fields__:  # type: ignore[attr-defined]
            default = defaults.get(name, dataclasses.MISSING)
            if isinstance(default, Field):
                one = dataclasses.field(default_factory=default.default_factory, kw_only=kw_only)
            else:
                one = dataclasses.field(default=default, kw_only=kw_only)
            made[name] = one
            one.name = name
            one.type = next((vars(b)["__annotations__"][name] for b in owner.__mro__
                             if name in vars(b).get("__annotations__", {})), None)
            one._field_type = dataclasses._FIELD  # type: ignore[attr-defined]
        type.__setattr__(owner, "__dataclass_fields__", made)
        return made
