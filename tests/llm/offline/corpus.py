"""The corpus of the offline translator's tests: one JSONL file per construct in ``corpus/`` (the
eval-translation format of docs/llm.md), each mission a sentence and the formula it must mean (the same
language under the scene's facts) or a fragment of the refusal it must get."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest
from _pytest.mark import ParameterSet

from sgplan.llm.evaluate import load_jsonl_set
from sgplan.llm.offline import PatternTranslator
from sgplan.llm.offline.evaluation import EvalMission, evaluate
from tests.shared_data import scene_building

CORPUS = Path(__file__).parent / "corpus"
SETS = Path(__file__).parent / "sets"


def constructs() -> list[str]:
    """The names of the corpus files (one per construct)."""
    return sorted(p.stem for p in CORPUS.glob("*.jsonl"))


def corpus(construct: str) -> list[EvalMission]:
    """The missions of ``corpus/<construct>.jsonl``."""
    return load_jsonl_set(CORPUS / f"{construct}.jsonl")


def cases(construct: str) -> list[ParameterSet]:
    """The missions of a construct as test parameters (by id; those over a Gibson scene marked ``gibson``)."""
    return [pytest.param(m, id=m.id, marks=() if m.scene == "demo" else (pytest.mark.gibson,))
            for m in corpus(construct)]


def check(mission: EvalMission) -> None:
    """``mission`` is translated to a formula meaning its gold, or refused with its fragment."""
    (result,) = evaluate(PatternTranslator(), [mission], scene_building)
    assert result.outcome == "right", f"{mission.id}: {mission.text!r}: {result.detail}"


def corpus_test(construct: str) -> Callable[[EvalMission], None]:
    """The test of ``corpus/<construct>.jsonl``: each of its missions is read or refused as it says."""
    @pytest.mark.parametrize("mission", cases(construct))
    def test(mission: EvalMission) -> None:
        check(mission)
    test.__doc__ = f"corpus/{construct}.jsonl: each sentence means its gold formula or gets its refusal."
    return test
