"""Comparisons in words on README.md and the documentation pages are checked against the
reports (studies.engine.comparisons): today's pages pass; for each kind of check a planted
contradiction (a page saying what the referee found, or a report altered in a temporary
copy) is named with its page and line; so are a comparison word no entry covers, a listed
fragment the page lost, an exception that holds, and a test that does not exist."""
import shutil
from pathlib import Path

from studies.engine import comparisons
from studies.engine.claims import ROOT

CARDS = 'table = "reports/cards/*.md"'


def _root(tmp_path: Path, page: str, listing: str, altered: dict[str, tuple[str, str]] | None = None) -> Path:
    """A project with README.md as its one page, the real reports (linked), and ``altered``
    reports copied with one text replaced: {name: (old, new)}."""
    (tmp_path / "docs").mkdir(parents=True)
    (tmp_path / "README.md").write_text(page)
    (tmp_path / "listing.toml").write_text(listing)
    reports = tmp_path / "reports"
    reports.mkdir()
    for f in (ROOT / "reports").iterdir():
        if f.name not in (altered or {}):
            (reports / f.name).symlink_to(f)
    for name, (old, new) in (altered or {}).items():
        text = (ROOT / "reports" / name).read_text()
        assert old in text
        (reports / name).write_text(text.replace(old, new))
    return tmp_path


def _problems(root: Path) -> list[str]:
    return comparisons.problems(root, root / "listing.toml")


def test_the_pages_compare_nothing_their_reports_contradict():
    assert comparisons.problems() == []


def test_above_the_referees_plateaus_are_caught_in_eight_of_the_twelve_cards(tmp_path):
    """The sentence pressure-elements.md had: plane-stress plateaus above plane-strain ones."""
    root = _root(tmp_path, "# Plateaus\n\nThe cards give each plateau per law and model;\nthe plane-stress plateaus "
                 "are above the plane-strain ones.\n",
                 '[[comparison]]\npage = "README.md"\ntext = "the plane-stress plateaus are above the plane-strain ones"\n'
                 f'kind = "above"\na = {{ {CARDS}, rows = {{ formulation = "plane-stress" }}, columns = ["plateau"], '
                 f'key = ["law"] }}\nb = {{ {CARDS}, rows = {{ formulation = "plane-strain" }}, columns = ["plateau"], '
                 'key = ["law"] }\n')
    found = _problems(root)
    assert found and all(p.startswith("README.md:4: 'the plane-stress plateaus are above") for p in found), found
    cards = {p.split(": above: ")[1].split("/")[0] for p in found}
    assert cards == {"HB2n-12", "HB2n-16", "HB2n-20", "HB2n-20xy", "HB2n-20xyp", "HB2n-20xypm", "HB3n-12", "LB2n-12"}
    assert any("HB2n-12/MR: 0.179 is not above 0.362" in p for p in found)


def test_same_the_referees_yeoh_cells_and_an_altered_record_are_caught(tmp_path):
    """"By the same amount for every element" (LB2n-12 differs otherwise), and the listed
    sentence of the pages once a deviation of HB3n-12 is altered in a copy of the report."""
    entry = ('[[comparison]]\npage = "README.md"\ntext = "by the same amount for every element"\nkind = "same"\n'
             'values = { table = "reports/table3_deviation.csv", rows = { formulation = "paper" }, '
             'columns = ["Yeoh ux (%)", "Yeoh uy (%)"], key = ["element"] }\ntol = 0.015\n')
    page = "Our Yeoh cells differ from the paper's\nby the same amount for every element.\n"
    found = _problems(_root(tmp_path / "a", page, entry))
    assert [p.split(": same: ")[1].split(" ")[0] for p in found] == ["Yeoh", "Yeoh"]
    assert all(p.startswith("README.md:2: ") for p in found), found
    assert _problems(_root(tmp_path / "b", page, entry + 'except = ["LB2n-12"]\n')) == []
    found = _problems(_root(tmp_path / "d", page, entry + 'except = ["LB2n-12"]\n', {
        "table3_deviation.csv": ("-0.43439791678524947", "-0.5")}))
    assert len(found) == 1 and found[0].startswith("README.md:2: ") and "Yeoh ux (%): spread 0.06" in found[0], found


def test_same_pairwise_the_referees_paper_rows_are_caught_at_lb2n12(tmp_path):
    """"Our `paper` rows print as the paper's": LB2n-12's are 6.4-6.6 % off in uy."""
    cols = '["NH ux (mm)", "NH uy (mm)", "MR ux (mm)", "MR uy (mm)"]'
    root = _root(tmp_path, "Here our `paper` rows print as the paper's.\n",
                 '[[comparison]]\npage = "README.md"\ntext = "our `paper` rows print as the paper\'s"\nkind = "same"\n'
                 f'a = {{ table = "reports/table3.csv", rows = {{ row = \'/^(\\S+) `paper`$/\' }}, columns = {cols} }}\n'
                 f'b = {{ table = "reports/table3.csv", rows = {{ row = \'/^paper (\\S+)$/\' }}, columns = {cols} }}\n'
                 'tol = 0.01\n')
    found = _problems(root)
    assert found and all(p.startswith("README.md:1: ") and ": same: LB2n-12/" in p for p in found), found


def test_least_an_altered_continuum_order_is_caught(tmp_path):
    page = "In the references plane stress converges more slowly than plane strain.\n"
    entry = ('[[comparison]]\npage = "README.md"\ntext = "plane stress converges more slowly than plane strain"\n'
             'kind = "least"\nvalues = { table = "reports/continuum_reference.csv", columns = ["order"], '
             'key = ["law", "model"] }\nexpect = "plane stress (F33 = 1/J)"\n')
    assert _problems(_root(tmp_path / "a", page, entry)) == []
    found = _problems(_root(tmp_path / "b", page, entry, {"continuum_reference.csv": (",1.5973367438575303,", ",9.6,")}))
    assert len(found) == 1 and found[0].startswith("README.md:1: ") and "least: neo-hookean: the least is plane strain, " \
        "penalty 1000 MPa (3.86819), not plane stress (F33 = 1/J) (9.6)" in found[0], found


def test_every_the_referees_defaults_are_caught_and_an_exception_must_fail(tmp_path):
    """"The default passes both tests": four cards have defaults that fail the finite-strain
    one; an exception that holds is named too."""
    entry = ('[[comparison]]\npage = "README.md"\ntext = "every default passes both"\nkind = "every"\n'
             f'values = {{ {CARDS}, columns = ["default (plane stress)", "default (penalised)"], key = ["l_e / h"] }}\n'
             'op = "lacks"\nbound = "✗"\n')
    found = _problems(_root(tmp_path / "a", "With its rules\nevery default passes both.\n", entry))
    assert all(p.startswith("README.md:2: ") for p in found), found
    assert {p.split(": every: ")[1].split("/")[0] for p in found} == {"HB2n-12", "HB2n-20", "HB2n-40p", "HC2n-8"}
    everything = ('except = ["HB2n-12/0.1/default (penalised)", "HB2n-20", "HB2n-40p/0.025", "HB2n-40p/0.01", '
                  '"HC2n-8", "HB2n-16"]\n')
    found = _problems(_root(tmp_path / "b", "With its rules\nevery default passes both.\n", entry + everything))
    assert found == ["README.md:2: 'every default passes both': every: HB2n-16: named as an exception, but every "
                     "value of it holds lacks '✗'"]


def test_an_unlisted_comparison_a_lost_fragment_and_a_missing_test_are_named(tmp_path):
    page = ("# Elements\n\nHB2n-40p lies above HB2n-12 here, and the table above\nlists them. Every run ends.\n"
            "HB2n-12 is the cheapest.\n")
    listing = ('[[not_a_comparison]]\npage = "README.md"\ntext = "the table above"\nwhy = "where it is"\n'
               '[[tested]]\npage = "README.md"\ntext = "HB2n-12 is the cheapest"\ntests = ["tests/test_rank.py::no_such"]\n'
               '[[not_a_comparison]]\npage = "README.md"\ntext = "a sentence that went"\nwhy = "-"\n')
    found = _problems(_root(tmp_path, page, listing))
    assert found == [
        "README.md:5: 'HB2n-12 is the cheapest': its test tests/test_rank.py::no_such does not exist",
        "listing.toml: README.md: 'a sentence that went' is no longer on the page",
        "README.md:3: 'above' compares in words, in a fragment listing.toml does not list: "
        "'HB2n-40p lies above HB2n-12 here, and the table above lists them.'"]
    assert comparisons.prose("a\n\n```\nHB2n-12 above\n```\n<!-- include x -->\nHB2n-12 above\n<!-- /include -->\n")[0] == "a"
