"""The documentation keeps up with the code: every command, option and output column is
documented, the README opens with the two commands that set up, its library example runs, its
exit codes are those of ``ExitCode``, every relative link leads somewhere, and the architecture
page's column map names functions that exist."""

from __future__ import annotations

import importlib
import re
import shutil
from functools import cache
from pathlib import Path

import pytest
from click.testing import CliRunner

from grainclass import __version__
from grainclass.cli import cli
from grainclass.cli.exit_codes import ExitCode
from grainclass.schema import GRAIN_SCHEMA

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()
DOCS = sorted((ROOT / "docs").glob("*.md"))
PAGES = [ROOT / "README.md", ROOT / "CHANGELOG.md", *DOCS]
EVERYTHING = "\n".join(page.read_text() for page in [ROOT / "README.md", *DOCS])
ARCHITECTURE = (ROOT / "docs" / "architecture.md").read_text()


def _section(text: str, heading: str) -> str:
    """The body of the ``## heading`` section of a Markdown text (up to the next ``## ``)."""
    body = text.split(f"\n## {heading}\n", 1)[1]
    return body.split("\n## ", 1)[0]


def _long_flags() -> list[tuple[str, str]]:
    """(command, --flag) for every long flag of the group and of every command, the negative
    of an on/off flag included (``--no-types``)."""
    flags = []
    for name, params in [("grainclass", cli.params)] + [
        (command, cli.commands[command].params) for command in sorted(cli.commands)
    ]:
        for param in params:
            for flag in [*param.opts, *getattr(param, "secondary_opts", [])]:
                if flag.startswith("--"):
                    flags.append((name, flag))
    return flags


@pytest.mark.parametrize("command", sorted(cli.commands))
def test_every_command_has_help(command):
    result = CliRunner().invoke(cli, [command, "--help"])
    assert result.exit_code == 0
    assert cli.commands[command].help
    assert "Exit codes" in result.output


@pytest.mark.parametrize("command", sorted(cli.commands))
def test_readme_documents_every_command(command):
    assert f"grainclass {command}" in README


@pytest.mark.parametrize(("command", "flag"), _long_flags())
def test_every_option_is_documented(command, flag):
    assert re.search(rf"(?<![\w-]){re.escape(flag)}(?![\w-])", EVERYTHING), (
        f"{command} {flag} is in neither README.md nor docs/*.md"
    )


@pytest.mark.parametrize("column", GRAIN_SCHEMA.names)
def test_readme_documents_every_output_column(column):
    assert f"`{column}`" in README


def test_readme_opens_with_make_demo_and_make_test():
    first_block = README.split("```sh\n", 1)[1].split("```", 1)[0].splitlines()
    assert [line.split("#")[0].strip() for line in first_block] == ["make demo", "make test"]


def test_readme_is_for_reading_not_for_scrolling():
    assert len(README.splitlines()) <= 250


def test_readme_links_every_docs_page():
    for page in DOCS:
        assert f"(docs/{page.name}" in README, f"README does not link docs/{page.name}"


def test_readme_exit_codes_are_those_of_exit_code():
    section = _section(README, "Exit codes")
    rows = re.findall(r"^\| (\d+) \|", section, re.MULTILINE)
    listed = [ExitCode.OK, ExitCode.FAILURE, ExitCode.USAGE, ExitCode.INTERRUPTED]
    listed.append(ExitCode.BROKEN_PIPE)
    assert [int(code) for code in rows] == [int(code) for code in listed]
    for code in (ExitCode.HANGUP, ExitCode.TERMINATED):
        assert str(int(code)) in section


def test_readme_library_example_runs(tmp_path, monkeypatch):
    """The README's Python block runs as written, on the tour's ``dataset.txt``, and every line
    ending in a number as its comment gives that number."""
    block = README.split("```python\n", 1)[1].split("```", 1)[0]
    shutil.copy(ROOT / "examples" / "polytopes.txt", tmp_path / "dataset.txt")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(block, namespace)
    for line in block.splitlines():
        code, _, comment = line.partition("#")
        if comment.strip().isdigit():
            assert eval(code, namespace) == int(comment)


def test_library_page_runs_in_order_from_the_repository_root(monkeypatch, capsys):
    """Every Python block of docs/library.md runs, one after another in one namespace, from the
    repository root, as a reader pastes them; the blocks' own asserts check what they say."""
    page = (ROOT / "docs" / "library.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", page, re.DOTALL)
    assert len(blocks) >= 5
    monkeypatch.chdir(ROOT)
    namespace: dict = {}
    for block in blocks:
        exec(block, namespace)
    assert "cube" in capsys.readouterr().out


@cache
def _anchors(path: Path) -> frozenset[str]:
    """The anchors GitHub gives the headings of a Markdown file (outside code blocks)."""
    anchors, fenced = set(), False
    for line in path.read_text().splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and line.startswith("#"):
            heading = line.lstrip("#").strip().lower()
            slug = re.sub(r"[^\w\- ]", "", heading).replace(" ", "-")
            anchor, n = slug, 1
            while anchor in anchors:
                anchor, n = f"{slug}-{n}", n + 1
            anchors.add(anchor)
    return frozenset(anchors)


def _relative_links() -> list[tuple[str, str]]:
    links = []
    for page in PAGES:
        text = re.sub(r"```.*?```", "", page.read_text(), flags=re.DOTALL)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if not re.match(r"[a-z]+:", target):
                links.append((str(page.relative_to(ROOT)), target))
    return links


@pytest.mark.parametrize(("page", "target"), _relative_links())
def test_relative_links_lead_somewhere(page, target):
    path, _, anchor = target.partition("#")
    source = ROOT / page
    linked = (source.parent / path).resolve() if path else source
    assert linked.exists(), f"{page} links {target}, which does not exist"
    if anchor and linked.suffix == ".md":
        assert anchor in _anchors(linked), f"{page} links {target}: no such heading"


def _column_map() -> dict[str, list[tuple[str, str]]]:
    """The architecture page's table: column -> the (module path, name) pairs its row names."""
    rows = {}
    for line in _section(ARCHITECTURE, "Where each column is computed").splitlines():
        found = re.match(r"\| `(\w+)` \|", line)
        if found:
            rows[found.group(1)] = re.findall(r"`([\w/]+\.py): ([\w.]+)`", line)
    return rows


def test_architecture_maps_every_column_to_a_function():
    rows = _column_map()
    assert set(rows) == set(GRAIN_SCHEMA.names)
    for column, functions in rows.items():
        assert functions or column == "area", f"no function named for {column}"


@pytest.mark.parametrize(
    ("path", "name"),
    sorted({pair for pairs in _column_map().values() for pair in pairs}),
)
def test_architecture_names_functions_that_exist(path, name):
    module = "grainclass." + path.removesuffix(".py").replace("/", ".")
    target = importlib.import_module(module.removesuffix(".__init__"))
    for attribute in name.split("."):
        assert hasattr(target, attribute), f"{path}: {name} does not exist"
        target = getattr(target, attribute)


def test_citation_names_this_version():
    yaml = pytest.importorskip("yaml")
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert citation["version"] == __version__
    assert citation["preferred-citation"]["title"] in " ".join(README.split())


def test_changelog_names_the_schema_version():
    from grainclass.schema import SCHEMA_VERSION

    changelog = (ROOT / "CHANGELOG.md").read_text()
    assert f"### Schema version {SCHEMA_VERSION} " in changelog
    assert GRAIN_SCHEMA.metadata[b"grainclass.schema_version"] == SCHEMA_VERSION.encode()


def test_make_test_lowest_pins_the_lower_bounds_of_pyproject():
    """``make test-lowest`` installs lowest-dependencies.txt: each runtime dependency at the
    lowest version pyproject.toml allows, and no other."""
    import tomllib

    from packaging.requirements import Requirement
    from packaging.version import Version

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    lowest = {}
    for line in project["dependencies"]:
        requirement = Requirement(line)
        (bound,) = [s.version for s in requirement.specifier if s.operator in (">=", "==")]
        lowest[requirement.name] = Version(bound)
    pinned = {}
    for line in (ROOT / "lowest-dependencies.txt").read_text().splitlines():
        if line and not line.startswith("#"):
            name, version = line.split("==")
            pinned[name] = Version(version)
    assert pinned == lowest
