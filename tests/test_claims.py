"""Numbers a reader meets outside the reports are quoted from a report or checked against
their source (studies.engine.claims): today's pages pass, and an unlisted number, a listed one
whose source moved, and a number inside a code block or a quoted report are told apart."""
from pathlib import Path

from studies.engine import claims


def test_the_readme_and_the_documentation_state_no_unchecked_number():
    assert claims.problems() == []


def test_an_unlisted_number_and_a_contradicted_source_are_named(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "README.md").write_text("The strip is 160 mm long and 9 mm thick.\n"
                                        "```python\nx = 3 %\n```\n"
                                        "<!-- include reports/x.md -->\n42 mm\n<!-- /include -->\n")
    listing = tmp_path / "numbers.toml"
    listing.write_text('[[number]]\ntext = "160 mm"\nsource = "contract.paper:CANTILEVER[\'length\']"\nscale = 1000\n'
                       '[[number]]\ntext = "9 mm"\nsource = "contract.paper:CANTILEVER[\'height\']"\nscale = 1000\n')
    found = claims.problems(tmp_path, listing)
    assert len(found) == 1 and "'9 mm': its source" in found[0] and "gives 5" in found[0]
    listing.write_text('[[number]]\ntext = "160 mm"\nsource = "contract.paper:CANTILEVER[\'length\']"\nscale = 1000\n')
    found = claims.problems(tmp_path, listing)
    assert found == [f"README.md:1: '9 mm' is neither quoted from a report nor listed with its source in "
                     f"{listing.relative_to(tmp_path)}"]
