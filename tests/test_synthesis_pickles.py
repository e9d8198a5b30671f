"""Objects pickled before ``linkage.synthesis`` became a package still load, and pickle the same.

``data/synthesis_objects_a3e9360.pickle`` was written by the single-module ``synthesis.py`` (and
``_precision.py``) of commit a3e9360 (protocol 4); ``….repr.json`` holds their reprs then.
"""

import io
import json
import pickle
import re
from pathlib import Path

import linkage._precision
from linkage import synthesis

DATA = Path(__file__).parent / "data"


def test_pickles_written_before_the_split_load_equal_and_pickle_to_the_same_bytes() -> None:
    data = (DATA / "synthesis_objects_a3e9360.pickle").read_bytes()
    objs = pickle.loads(data)
    reprs = json.loads((DATA / "synthesis_objects_a3e9360.repr.json").read_text(encoding="utf-8"))
    reprs = {k: re.sub(r", shape=\([\d, ]+\)", "", v) for k, v in reprs.items()}
    assert {k: _repr(v) for k, v in objs.items()} == reprs
    assert isinstance(objs["candidate"], synthesis.Candidate)
    assert isinstance(objs["candidates"], synthesis.Candidates)
    assert objs["candidates"].removed == {"lengths": 2}
    assert objs["candidates"].closest_removed == objs["candidate"]
    assert isinstance(objs["atlas"], synthesis.Atlas)
    assert isinstance(objs["function"], synthesis.FunctionGenerator)
    assert isinstance(objs["dyad"], synthesis.Dyad)
    # A new pickle names the same classes at the same paths (so it loads with 0.1 too).
    again = pickle.dumps(objs, protocol=4)
    assert _classes(again) == _classes(data)
    assert {k: _repr(v) for k, v in pickle.loads(again).items()} == reprs


def _repr(obj: object) -> str:
    """``repr(obj)`` as numpy < 2.2 writes it (2.2 adds ``shape=`` to a summarised array), so
    the reprs saved then compare on every numpy the wheel supports."""
    return re.sub(r", shape=\([\d, ]+\)", "", repr(obj))


def _classes(data: bytes) -> set[tuple[str, str]]:
    """Return the (module, name) of every class or function a pickle refers to."""
    seen: set[tuple[str, str]] = set()

    class Recorder(pickle.Unpickler):
        def find_class(self, module: str, name: str) -> object:
            seen.add((module, name))
            return super().find_class(module, name)

    Recorder(io.BytesIO(data)).load()
    return seen


def test_classes_keep_their_module_paths() -> None:
    for cls in (synthesis.Atlas, synthesis.Candidate, synthesis.Candidates, synthesis._Kind):
        assert cls.__module__ == "linkage.synthesis", cls
    for cls in (synthesis.Dyad, synthesis.MotionCandidate, synthesis.FunctionGenerator):
        assert cls.__module__ == "linkage._precision", cls
        assert getattr(linkage._precision, cls.__name__) is cls
