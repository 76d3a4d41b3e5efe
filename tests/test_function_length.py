"""No function in src/ is longer than 80 lines, except a compiled (numba) kernel whose docstring says why
it is one function (a sentence starting "One function", with its reason)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "sgplan"
MAX_LINES = 80
# "One function" and a reason of some words after it, in the same paragraph.
WHY_ONE_FUNCTION = re.compile(r"\bOne function\b[^\n]*(?:\n(?!\s*\n)[^\n]*)*", re.MULTILINE)


def _is_numba_kernel(node: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Decorated with numba's ``njit`` / ``jit`` (called or not, plain or as ``numba.njit``)."""
    for decorator in node.decorator_list:
        target = decorator.func if isinstance(decorator, ast.Call) else decorator
        name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
        if name in ("njit", "jit"):
            return True
    return False


def _says_why_one_function(docstring: str | None) -> bool:
    match = WHY_ONE_FUNCTION.search(docstring or "")
    return match is not None and len(match.group(0).split()) >= 12


def _long_functions() -> list[tuple[str, ast.FunctionDef | ast.AsyncFunctionDef, int]]:
    found = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = (node.end_lineno or node.lineno) - node.lineno + 1
                if lines > MAX_LINES:
                    found.append((f"{path.relative_to(SRC.parent)}:{node.lineno} {node.name}", node, lines))
    return found


def test_no_function_over_80_lines_but_kernels_that_say_why() -> None:
    kernel_note = ", a numba kernel whose docstring does not say why it is one function"
    too_long = [
        f"{where} ({lines} lines{kernel_note if _is_numba_kernel(node) else ''})"
        for where, node, lines in _long_functions()
        if not (_is_numba_kernel(node) and _says_why_one_function(ast.get_docstring(node)))
    ]
    assert not too_long, "split these (or, for a kernel, say why it is one function):\n" + "\n".join(too_long)


def test_the_reason_must_be_there() -> None:
    """The check reads the docstring: a bare phrase is not a reason."""
    assert not _says_why_one_function("One function.")
    assert not _says_why_one_function(None)
    assert _says_why_one_function(
        "Fast.\n\n    One function: a helper per step would take a dozen arrays, each reference-counted on "
        "every call."
    )
    kernel = ast.parse("@numba.njit(cache=True)\ndef f():\n    pass\n").body[0]
    plain = ast.parse("@functools.cache\ndef f():\n    pass\n").body[0]
    assert isinstance(kernel, ast.FunctionDef) and isinstance(plain, ast.FunctionDef)
    assert _is_numba_kernel(kernel) and not _is_numba_kernel(plain)
