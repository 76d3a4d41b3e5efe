"""How to plan: the planning options as one typed, validated, serialisable value, :class:`PlanOptions`.

The options are stated once, here, as the fields of a frozen dataclass, and everything else reads them from
it: :func:`sgplan.plan` and :meth:`sgplan.Session.plan` take them as keywords (checked against the fields
by :meth:`PlanOptions.from_keywords`), the CLI and the benchmark worker build one from their arguments, and
saved runs store :meth:`PlanOptions.to_dict` (JSON-safe). What is not an option but a collaborator of one
plan (the guide asked for guidance, the iteration callback, an explanation already made, the session, a
cancel flag) stays a parameter of its own.

>>> from sgplan.options import PlanOptions
>>> options = PlanOptions(setup="no-llm", time_limit_s=5)
>>> options.setup, options.profile
('NO-LLM', 'ltlf')
>>> PlanOptions.from_dict(options.to_dict()) == options
True
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from sgplan.errors import PlanningError
from sgplan.limits import MAX_REACH_RADIUS_M, MAX_ROBOT_RADIUS_M, MAX_SECONDS
from sgplan.planning.setups import check_profile, get_setup, reach_model_for

if TYPE_CHECKING:
    from sgplan.planning.termination import Termination


@dataclass(frozen=True)
class PlanOptions:
    """The options of one plan, validated when made (a bad value raises :class:`PlanningError` naming the
    option, the value and what is allowed).

    Attributes
    ----------
    setup:
        the paper's planner setup: ``ALL`` (default), ``NO-LLM``, ``A*``, ``OCC``, ``OBJ``, ``ROOM``,
        ``FLR``; given in any case (``NO_LLM``, ``a_star`` too), stored by its canonical name.
    profile:
        ``"ltlf"`` (default: the start cell's label is read, missing automaton edges reject) or
        ``"authors"`` (the authors' C++; docs/semantics.md); given in any case, stored in lower case.
    robot_radius_m, reach_radius_m:
        metres; ``None`` (default): the scene's, else 0 and 0.6. Robot radius in
        ``[0, MAX_ROBOT_RADIUS_M]``, reach radius in ``(0, MAX_REACH_RADIUS_M]`` (:mod:`sgplan.limits`);
        that the reach radius is not below the robot radius is checked when the scene's values are known
        (:func:`sgplan.radii.resolve_radii`).
    reach_model:
        where an object counts as reached (:mod:`sgplan.scene.reach`, docs/semantics.md): ``"visible"``
        (within the reach radius and in sight: walls block) or ``"box"`` (the authors' square window);
        given in any case, stored in lower case; ``None`` (default): the profile's (``ltlf`` visible,
        ``authors`` box), :attr:`effective_reach_model`.
    time_limit_s, max_expansions:
        search budgets: seconds of search (``(0, MAX_SECONDS]``) and expansions (``>= 0``); ``None``: no
        limit. When one runs out the plan has status ``"timeout"`` with the best path so far.
    verify:
        check the path and its cost with the independent checker (default ``True``).
    prebuild_actions:
        build every composite action map before the search starts (the paper's accounting of first-path
        times); default ``False``: each map is built when the search first needs it.
    """

    setup: str = "ALL"
    profile: str = "ltlf"
    robot_radius_m: float | None = None
    reach_radius_m: float | None = None
    reach_model: str | None = None
    time_limit_s: float | None = None
    max_expansions: int | None = None
    verify: bool = True
    prebuild_actions: bool = False

    def __post_init__(self) -> None:
        for name, value in (("setup", self.setup), ("profile", self.profile)):
            if not isinstance(value, str):
                raise PlanningError(f"planning option {name} must be a name, got {value!r}")
        self._set("setup", get_setup(self.setup).name)
        self._set("profile", check_profile(self.profile.strip().lower()))
        self._set("robot_radius_m", _number("robot_radius_m", self.robot_radius_m, 0.0, MAX_ROBOT_RADIUS_M,
                                            zero=True, unit="metres"))
        self._set("reach_radius_m", _number("reach_radius_m", self.reach_radius_m, 0.0, MAX_REACH_RADIUS_M,
                                            zero=False, unit="metres"))
        if self.reach_model is not None:
            self._set("reach_model", reach_model_for(self.profile, self.reach_model))
        self._set("time_limit_s", _number("time_limit_s", self.time_limit_s, 0.0, MAX_SECONDS, zero=False,
                                          unit="seconds"))
        expansions = self.max_expansions
        if expansions is not None:
            if not (_is_int(expansions) and expansions >= 0):
                raise PlanningError("planning option max_expansions must be a whole number >= 0, or None; "
                                    f"got {expansions!r}")
            self._set("max_expansions", int(expansions))
        for name in ("verify", "prebuild_actions"):
            value = getattr(self, name)
            if not isinstance(value, bool):
                raise PlanningError(f"planning option {name} must be True or False, got {value!r}")

    @property
    def effective_reach_model(self) -> str:
        """The reach model a plan with these options uses: :attr:`reach_model`, else the profile's."""
        return reach_model_for(self.profile, self.reach_model)

    def _set(self, name: str, value: Any) -> None:
        object.__setattr__(self, name, value)  # normalising a frozen dataclass's own field while it is made

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The options' names, in field order."""
        return tuple(f.name for f in dataclasses.fields(cls))

    @classmethod
    def from_keywords(cls, base: PlanOptions | None = None, /, **values: Any) -> PlanOptions:
        """``base`` (default: the defaults) with the options given as keywords replaced, validated.

        Raises
        ------
        TypeError
            a keyword that is no option, naming the valid ones (as for a function's unknown keyword).
        PlanningError
            a value the option does not allow.
        """
        unknown = sorted(set(values) - set(cls.names()))
        if unknown:
            raise TypeError(f"unknown planning option{'s' if len(unknown) > 1 else ''} "
                            f"{', '.join(unknown)}; the options are {', '.join(cls.names())}")
        return dataclasses.replace(base if base is not None else cls(), **values)

    def replace(self, **values: Any) -> PlanOptions:
        """These options with some replaced (validated again); see :meth:`from_keywords`."""
        return self.from_keywords(self, **values)

    def to_dict(self) -> dict[str, Any]:
        """The options as a JSON-safe dict (every option, by name; ``None`` for "the scene's" / no limit)."""
        return {name: getattr(self, name) for name in self.names()}

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> PlanOptions:
        """The options of a dict made by :meth:`to_dict` (options left out take their defaults).

        Raises
        ------
        PlanningError
            ``data`` is not a mapping, names no option, or holds a value the option does not allow.
        """
        if not isinstance(data, Mapping):
            raise PlanningError(f"planning options must be a mapping of option -> value, got {data!r}")
        unknown = sorted(str(key) for key in set(data) - set(cls.names()))
        if unknown:
            raise PlanningError(f"unknown planning option{'s' if len(unknown) > 1 else ''} "
                                f"{', '.join(unknown)}; the options are {', '.join(cls.names())}")
        return cls(**data)

    def termination(self) -> Termination | None:
        """The search's termination condition of the budgets (:mod:`sgplan.planning.termination`): the
        time limit, the expansion limit, either of both, or ``None`` without a budget."""
        from sgplan.planning.termination import ExpansionLimit, TimeLimit, any_of

        return any_of(TimeLimit(self.time_limit_s) if self.time_limit_s is not None else None,
                      ExpansionLimit(self.max_expansions) if self.max_expansions is not None else None)


def _is_int(value: Any) -> bool:
    """True for Python and numpy integers (numpy registers them as :class:`numbers.Integral`), not bools."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _number(name: str, value: Any, low: float, high: float, *, zero: bool, unit: str) -> float | None:
    """``value`` as a float if it is ``None`` or a finite number in ``[low, high]`` (``(low, high]`` unless
    ``zero``)."""
    if value is None:
        return None
    ok = isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or not (low <= value <= high) or (value == low and not zero):
        lower = ">=" if zero else ">"
        raise PlanningError(f"planning option {name} must be a number of {unit} {lower} {low:g} and <= "
                            f"{high:g}, or None; got {value!r}")
    return float(value)
