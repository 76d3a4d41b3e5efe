"""Prompt templates: versioned text files in ``sgplan/llm/prompts/``, rendered into chat messages.

A template file (format in docs/llm-pipeline.md) starts with ``#`` header lines, one of which is
``# version: <name>/<n>``; the version is stored with every call in the run record, so a recorded run says
which wording produced it. The body is either plain text (a *fragment*, e.g. the hierarchy preamble,
rendered with :meth:`PromptTemplate.text`) or a sequence of chat messages, each introduced by a line
``=== system ===``, ``=== user ===`` or ``=== assistant ===`` (rendered with :meth:`PromptTemplate.messages`).
Placeholders are :class:`string.Template` names (``$mission``); ``$$`` is a literal dollar sign.

Rendering is strict: a missing value, a value no placeholder uses, or a malformed placeholder is an
error, so a template and its caller cannot drift apart silently.
"""

from __future__ import annotations

import re
import string
from dataclasses import dataclass
from functools import cache
from importlib import resources

from sgplan.errors import LLMError
from sgplan.llm.client import ROLES

PROMPT_NAMES = ("hierarchy", "grounding", "grounding_repair", "translation", "repair", "guidance")
"""The templates shipped with sgplan."""

_VERSION = re.compile(r"^#\s*version:\s*(\S+)\s*$")
_ROLE = re.compile(r"^===\s*(\w+)\s*===\s*$")


@dataclass(frozen=True)
class PromptTemplate:
    """One parsed template file.

    Attributes
    ----------
    name:
        The file's stem, e.g. ``"grounding"``.
    version:
        The ``# version:`` header, e.g. ``"grounding/1"``.
    parts:
        ``(role, text)`` pairs; a fragment has one part with role ``None``.
    """

    name: str
    version: str
    parts: tuple[tuple[str | None, str], ...]

    @property
    def placeholders(self) -> frozenset[str]:
        """The placeholder names the template uses."""
        names: set[str] = set()
        for _, text in self.parts:
            names.update(_placeholders(string.Template(text), self.name))
        return frozenset(names)

    def messages(self, **values: str) -> list[dict[str, str]]:
        """The chat messages with every placeholder replaced; see :func:`load_prompt` for errors."""
        if self.parts[0][0] is None:
            raise LLMError(f"prompt {self.name!r} is a text fragment, not a chat; use .text()")
        rendered = self._render(values)
        roles = [role for role, _ in self.parts if role is not None]  # a chat: every part has its role
        return [{"role": role, "content": text} for role, text in zip(roles, rendered)]

    def text(self, **values: str) -> str:
        """The fragment with every placeholder replaced."""
        if self.parts[0][0] is not None:
            raise LLMError(f"prompt {self.name!r} is a chat, not a text fragment; use .messages()")
        return self._render(values)[0]

    def _render(self, values: dict[str, str]) -> list[str]:
        expected = self.placeholders
        missing = sorted(expected - values.keys())
        unused = sorted(values.keys() - expected)
        if missing or unused:
            raise LLMError(
                f"prompt {self.version}: values missing for {missing or 'none'}, given but unused "
                f"{unused or 'none'}"
            )
        return [string.Template(text).substitute(values).strip() for _, text in self.parts]


def _placeholders(template: string.Template, name: str) -> set[str]:
    names: set[str] = set()
    for match in template.pattern.finditer(template.template):
        if match.group("invalid") is not None:
            raise LLMError(
                f"prompt template {name!r}: a '$' that starts no placeholder (write $$ for a dollar)"
            )
        found = match.group("named") or match.group("braced")
        if found:
            names.add(found)
    return names


def parse_template(name: str, source: str) -> PromptTemplate:
    """Parse the text of a template file named ``name`` (see the module docstring).

    Raises
    ------
    LLMError
        no ``# version:`` header, an unknown role, text before the first role line of a chat, or an empty
        body.
    """
    lines = source.splitlines()
    header_end = next((i for i, line in enumerate(lines) if not line.startswith("#")), len(lines))
    versions = [m.group(1) for m in map(_VERSION.match, lines[:header_end]) if m]
    if len(versions) != 1:
        raise LLMError(f"prompt template {name!r}: expected one '# version: {name}/<n>' header line")
    body = lines[header_end:]
    parts: list[tuple[str | None, list[str]]] = []
    for line in body:
        role = _ROLE.match(line)
        if role:
            if role.group(1) not in ROLES:
                raise LLMError(f"prompt template {name!r}: unknown role {role.group(1)!r} (expected {ROLES})")
            parts.append((role.group(1), []))
        elif parts:
            parts[-1][1].append(line)
        elif line.strip():
            if any(_ROLE.match(other) for other in body):
                raise LLMError(f"prompt template {name!r}: text before the first '=== role ===' line")
            parts.append((None, []))
            parts[-1][1].append(line)
    texts = tuple((role, "\n".join(chunk)) for role, chunk in parts)
    if not texts or any(not text.strip() for _, text in texts):
        raise LLMError(f"prompt template {name!r}: empty body or empty message")
    for _, text in texts:  # reject a stray '$' when the file is read, not at first use
        _placeholders(string.Template(text), name)
    return PromptTemplate(name, versions[0], texts)


@cache
def load_prompt(name: str) -> PromptTemplate:
    """The shipped template ``name`` (one of :data:`PROMPT_NAMES`), parsed once per process.

    Raises :class:`LLMError` for an unknown name or a malformed file.

    Example
    -------
    >>> load_prompt("repair").version
    'repair/1'
    """
    if name not in PROMPT_NAMES:
        raise LLMError(f"unknown prompt {name!r} (shipped: {', '.join(PROMPT_NAMES)})")
    source = (resources.files("sgplan.llm") / "prompts" / f"{name}.txt").read_text(encoding="utf-8")
    return parse_template(name, source)
