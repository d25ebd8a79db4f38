"""The Python 3.10 stand-in for tomllib agrees with it on the scene-file subset and refuses the rest."""
import math
import sys

import pytest
from hypothesis import given, settings, strategies as st

from symlink.minitoml import loads

tomllib = pytest.importorskip("tomllib") if sys.version_info >= (3, 11) else None

EXAMPLE = """\
# A scene.
linkage = "fourbar"          # catalog name
outputs = ["rocker", "rocker_speed",]
branch = "both"

[parameters]
a = 20
b = 6.6e1
c = +56.0
d = 8_0

[input]
angles = [0, -40.5, 1e-3]
speed = -inf
flag = true
odd = nan
"""


def test_example():
    document = loads(EXAMPLE)
    assert document["outputs"] == ["rocker", "rocker_speed"]
    assert document["parameters"] == {"a": 20, "b": 66.0, "c": 56.0, "d": 80}
    assert document["input"]["angles"] == [0, -40.5, 0.001] and document["input"]["flag"] is True
    assert document["input"]["speed"] == -math.inf and math.isnan(document["input"]["odd"])
    assert isinstance(document["parameters"]["a"], int) and isinstance(document["parameters"]["c"], float)
    if tomllib:
        expected = tomllib.loads(EXAMPLE)
        assert math.isnan(expected["input"].pop("odd")) and document["input"].pop("odd")
        assert document == expected


keys = st.from_regex(r"[A-Za-z0-9_-]{1,8}", fullmatch=True)
scalars = st.one_of(
    st.integers(-10**12, 10**12).map(lambda v: (str(v), v)),
    st.floats(allow_nan=False).map(lambda v: (repr(v), v)),
    st.booleans().map(lambda v: (str(v).lower(), v)),
    st.text(st.characters(blacklist_categories=("Cc", "Cs"), blacklist_characters='"\\#[],'),
             max_size=10).map(lambda v: (f'"{v}"', v)),
)
values = st.one_of(scalars, st.lists(scalars, max_size=4).map(
    lambda items: ("[" + ", ".join(text for text, _ in items) + "]", [v for _, v in items])))
tables = st.dictionaries(keys, values, max_size=4)


@pytest.mark.skipif(tomllib is None, reason="tomllib is the reference (Python 3.11+)")
@settings(max_examples=150, deadline=None)
@given(tables, st.dictionaries(keys, tables, max_size=3))
def test_same_as_tomllib_on_the_subset(top, named):
    top = {k: v for k, v in top.items() if k not in named}
    lines = [f"{k} = {text}" for k, (text, _) in top.items()]
    for name, table in named.items():
        lines += [f"[{name}]  # a table"] + [f"{k}={text}" for k, (text, _) in table.items()]
    text = "\n".join(lines) + "\n"
    assert loads(text) == tomllib.loads(text)


@pytest.mark.parametrize("text, message", [
    ('a = "x\\ny"\n', "escapes"),
    ("a = 'x'\n", "not a value"),
    ("a = [1, [2]]\n", "nested"),
    ("a = [1,\n 2]\n", "same line"),
    ("a = 1\na = 2\n", "defined twice"),
    ("[t]\n[t]\n", "defined twice"),
    ("a.b = 1\n", "expected 'key = value'"),
    ("a = 0x10\n", "not a value"),
    ("a = 01\n", "not a value"),
    ("a = 1.\n", "not a value"),
    ("a = True\n", "not a value"),
    ("a = 1979-05-27\n", "not a value"),
    ("a = {x = 1}\n", "not a value"),
    ("[[array]]\n", "expected 'key = value'"),
    ("a = [1 2]\n", "expected ','"),
    ("just words\n", "expected 'key = value'"),
])
def test_outside_the_subset_is_an_error_naming_the_line(text, message):
    with pytest.raises(ValueError, match=f"line [12]: .*{message}"):
        loads(text)
