"""Hard edges of every reader of another format (issue #32, item 5): as strict as the linkage file.

Table-driven: each bad text is refused by one short ``ValueError`` (never an ``OverflowError``, a
``RecursionError`` or a silently kept value), and good text that differs only in harmless ways (a byte-order
mark, CRLF line ends, comments) reads to the same linkage.  The expected joints are counted in the text written
here, independently of the readers.
"""
import json

import pytest

import symlink
from symlink.common.numbers import json_data, toml_data
from symlink.io.linkage_file import MAX_LINKAGE_BYTES, linkage_from_mapping, linkage_from_text
from symlink.io.pylinkage import read_pylinkage, write_pylinkage
from symlink.io.pyslvs import read_pyslvs
from symlink.studio.drawing import open_source
from symlink.workshop.fabrication import design_json, read_design

FOURBAR = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0}
_JOINT_FILE = """name = "fourbar"
driver = "A"

[links]
ground = ["A", "D"]
crank = ["A", "B"]
coupler = ["B", "C", "P"]
rocker = ["D", "C"]

[joints]
A = [0, 0]
B = [0, 20]
C = [60, 50]
D = [80, 0]
P = [30, 60]
"""


_PYLINKAGE = ('{"name": "fourbar", "joints": [{"id": "A", "type": "ground", "position": [0, 0]}, '
              '{"id": "D", "type": "ground", "position": [80, 0]}, '
              '{"id": "B", "type": "revolute", "position": [0, 20]}, '
              '{"id": "C", "type": "revolute", "position": [60, 50]}], '
              '"links": [{"id": "ground", "type": "ground", "joints": ["A", "D"]}, '
              '{"id": "crank", "type": "driver", "joints": ["A", "B"], "motor_joint": "A"}, '
              '{"id": "coupler", "type": "link", "joints": ["B", "C"]}, '
              '{"id": "rocker", "type": "link", "joints": ["D", "C"]}]}')


def _design_text() -> str:
    return design_json(symlink.fourbar(), FOURBAR, "mm")


def _one_short_line(error: pytest.ExceptionInfo) -> None:
    message = str(error.value)
    assert len(message) < 250 and "\n" not in message, message


# --- JSON: one strict reader (symlink.common.numbers.json_data) for every JSON a user hands over -------------------

JSON_READERS = {
    "pylinkage": (lambda text: read_pylinkage(text), _PYLINKAGE),
    "design": (lambda text: read_design(text, "design.json"), None),
    "studio": (lambda text: open_source(text), _PYLINKAGE),
}


def _bad_json(base: str) -> list[tuple[str, str, str]]:
    first_key = base[:base.index(":") + 1]  # '{"name":' or '{\n "format":'
    return [
        ("a key given twice", base.replace(first_key, first_key + ' "x", ' + first_key.lstrip("{ \n"), 1),
         "given twice"),
        ("a number of 400 digits", base.replace("[0, 0]", "[0, 1" + "0" * 400 + "]", 1) if "[0, 0]" in base
         else base.replace('"version": 1', '"version": 1' + "0" * 400, 1), "out of range|too large"),
        ("1e-400", base.replace("[0, 0]", "[0, 1e-400]", 1) if "[0, 0]" in base
         else base.replace('"version": 1', '"version": 1e-400', 1), "too small|out of range"),
        ("NaN", base.replace("[0, 0]", "[0, NaN]", 1) if "[0, 0]" in base
         else base.replace('"version": 1', '"version": NaN', 1), "NaN"),
        ("nested a million deep", "[" * 1_000_000 + "]" * 1_000_000, "nested too deeply|more than|at most"),
        ("empty", "", "JSON|give"),
    ]


JSON_CASES = [(reader, what, text, words)
              for reader, (_, base) in JSON_READERS.items()
              for what, text, words in _bad_json(base if base is not None else _design_text())]


@pytest.mark.parametrize("reader, what, text, words", JSON_CASES,
                         ids=[f"{reader}-{what}" for reader, what, _, _ in JSON_CASES])
def test_bad_json_is_one_short_value_error(reader, what, text, words):
    assert text != (JSON_READERS[reader][1] or _design_text()) or what == "empty"
    with pytest.raises(ValueError, match=words) as refused:
        JSON_READERS[reader][0](text)
    _one_short_line(refused)


def test_the_good_json_of_each_reader_is_read():
    assert read_pylinkage(_PYLINKAGE).build().linkage.unknowns
    assert read_design(_design_text()).values == FOURBAR
    assert open_source(_PYLINKAGE)["joints"]


@pytest.mark.parametrize("text, expected", [
    ('{"a": 1, "b": [2.5, -3]}', {"a": 1, "b": [2.5, -3]}),
    ('\ufeff{"a": 1}', {"a": 1}),
    ('{"a": {"a": 1}}', {"a": {"a": 1}}),  # the same key in two objects is no repeat
])
def test_json_data_reads_what_json_reads(text, expected):
    assert json_data(text) == expected == json.loads(text.lstrip("\ufeff"))


# --- Pyslvs: a comment ends where it ends; no joint after it is dropped --------------------------------------------

_JOINTS = ["J[R, P[0, 0], L[ground, crank]]", "J[R, P[0, 20], L[crank, coupler]]",
           "J[R, P[60, 50], L[coupler, rocker]]", "J[R, P[80, 0], L[ground, rocker]]", "J[R, P[30, 60], L[coupler]]"]


@pytest.mark.parametrize("text, joints", [
    ("M[" + ", ".join(_JOINTS) + "]", 5),
    # a joint after a block comment on the same line (the comment once ran to the end of its line)
    ("M[" + _JOINTS[0] + ", #[ the crank #] J[R, P[0, 100], L[crank]],\n" + ", ".join(_JOINTS[1:]) + "]", 6),
    # two block comments: what lies between them is read (the comment once ran to the last #])
    ("M[" + _JOINTS[0] + ", #[ one #]\n" + ", ".join(_JOINTS[1:3]) + ", #[ two #]\n" + ", ".join(_JOINTS[3:]) + "]", 5),
    ("M[" + _JOINTS[0] + ", # a line comment #[ not a block\n" + ", ".join(_JOINTS[1:]) + "]", 5),
    ("\ufeffM[" + ",\r\n".join(_JOINTS) + "]", 5),  # a byte-order mark and CRLF line ends
], ids=["plain", "a joint after a block comment", "two block comments", "a line comment", "BOM and CRLF"])
def test_every_joint_outside_comments_is_read(text, joints):
    assert len(read_pyslvs(text).build().linkage.points) == joints


@pytest.mark.parametrize("text, words", [
    ("M[" + _JOINTS[0] + ", #[ never closed\n" + ", ".join(_JOINTS[1:]) + "]", "never ends"),
    ("M[" + "#[ " * 200_000, "never ends"),
], ids=["unterminated block comment", "many unterminated"])
def test_a_comment_that_never_ends_is_refused(text, words):
    with pytest.raises(ValueError, match=words) as refused:
        read_pyslvs(text)
    _one_short_line(refused)


# --- linkage files' text: the same bounds as the file reader's, numbers of any digits in one line ------------------

@pytest.mark.parametrize("text, words", [
    (_JOINT_FILE + "#" * (MAX_LINKAGE_BYTES + 1), "more than a linkage file may hold|at most"),
    (_JOINT_FILE.replace("D = [80, 0]", "D = [1" + "0" * 400 + ", 0]"), "finite number"),
    (_JOINT_FILE.replace("D = [80, 0]", "D = [1" + "0" * 5000 + ", 0]"), "too large for a float"),
    (_JOINT_FILE.replace("D = [80, 0]", "D = [true, 0]"), "must be a number, got True"),
    (_JOINT_FILE.replace('driver = "A"', 'driver = ["A", "A"]'), "driver lists 'A' more than once"),
], ids=["over the size cap", "a 400-digit integer", "a 5000-digit integer", "a boolean", "a driver twice"])
def test_bad_linkage_text_is_one_short_value_error(text, words):
    for read in (linkage_from_text, open_source):
        with pytest.raises(ValueError, match=words) as refused:
            read(text)
        _one_short_line(refused)


def test_a_5000_digit_integer_names_its_line_not_pythons_digit_limit():
    with pytest.raises(ValueError) as refused:
        toml_data("a = 1\nb = 1" + "0" * 5000 + "\n")
    assert str(refused.value).startswith("line 2:") and "set_int_max_str_digits" not in str(refused.value)


@pytest.mark.parametrize("prefix", ["\ufeff", ""])
def test_a_byte_order_mark_is_dropped_by_every_text_reader(prefix):
    assert len(linkage_from_text(prefix + _JOINT_FILE.replace("\n", "\r\n")).linkage.points) == 5
    assert len(read_pylinkage(prefix + _PYLINKAGE).build().linkage.points) == 4
    assert len(open_source(prefix + _JOINT_FILE)["joints"]) == 5


# --- mappings handed over in Python: a huge integer is refused in one line, never an OverflowError ----------------

@pytest.mark.parametrize("read", [
    lambda: read_pylinkage({**json.loads(_PYLINKAGE), "joints": [
        {"id": "A", "type": "ground", "position": [10 ** 400, 0]}, *json.loads(_PYLINKAGE)["joints"][1:]]}),
    lambda: linkage_from_mapping({**toml_data(_JOINT_FILE), "joints": {
        **toml_data(_JOINT_FILE)["joints"], "D": [10 ** 400, 0]}}),
], ids=["pylinkage", "joint tables"])
def test_a_huge_integer_in_a_mapping_is_a_value_error(read):
    with pytest.raises(ValueError, match="finite") as refused:
        read()
    _one_short_line(refused)
