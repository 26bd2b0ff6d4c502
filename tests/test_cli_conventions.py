"""CLI conventions: every option of every command has help text, a metavar that is not
click's type name, its default shown when it has one, -o/--output for output files, one
spelling (color, center); the top-level help groups the commands by workflow."""
import click
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import COMMANDS, SECTIONS, cli

#: commands checked for spelling only (none)
OTHERS = set()


def options_of(name):
    cmd = cli.get_command(click.Context(cli), name)
    return [p for p in cmd.params if isinstance(p, click.Option) and not p.hidden]


@pytest.mark.parametrize("name", sorted(set(COMMANDS) - OTHERS))
def test_every_option_is_documented(name):
    for p in options_of(name):
        where = f"{name} {p.opts[0]}"
        assert p.help, f"{where}: no help text"
        if not p.is_flag and not isinstance(p.type, click.Choice) and p.count is False:
            assert p.metavar, f"{where}: click's metavar ({p.type.name.upper()}) would show"
        if (p.default not in (None, False, ()) and not p.is_flag and p.required is False
                and not callable(p.default) and repr(p.default) != "Sentinel.UNSET"):
            assert p.show_default, f"{where}: default {p.default!r} not shown"


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_one_spelling_and_output_option(name):
    for p in options_of(name):
        for o in p.opts:
            assert "colour" not in o and "centre" not in o, f"{name} {o}: spell color, center"
            assert o != "--out", f"{name}: --out is -o/--output"


def test_help_groups_commands_by_workflow():
    out = CliRunner().invoke(cli, ["--help"]).output
    heads = [line for line in out.splitlines() if line.startswith("Commands: ")]
    assert heads == [f"Commands: {s}:" for s in SECTIONS]
    listed = {n for names in SECTIONS.values() for n in names}
    assert listed == set(COMMANDS)
    for name in COMMANDS:
        assert f"\n  {name} " in out


def test_center_keeps_its_old_spelling_as_a_deprecated_alias(tmp_path):
    path = tmp_path / "d.json"
    run = CliRunner().invoke
    assert run(cli, ["import", "--rectangle", "300x200", "-o", str(path)]).exit_code == 0
    r = run(cli, ["place", str(path), "--piece", "rectangle", "--grid", "1x2", "--pitch", "60",
                  "--centre", "150,100", "-d", "40", "-p", "0.7"])
    assert r.exit_code == 0, r.output
    assert "Warning: --centre is deprecated; use --center" in r.stderr


def test_place_and_inverse_share_the_inverse_target_options():
    """--radius, --max-diameter, --min-fill come from one declaration (cli/options.py): the
    same destination, type and metavar in both commands; place's help says they apply with
    --height, inverse's does not, and both say the unit and the default."""
    place = {p.opts[0]: p for p in options_of("place")}
    inverse = {p.opts[0]: p for p in options_of("inverse")}
    for opt, dest, unit in (("--radius", "radius_mm", "in mm"),
                            ("--max-diameter", "max_diameter_mm", "in mm"),
                            ("--min-fill", "min_fill", "fill")):
        a, b = place[opt], inverse[opt]
        assert (a.name, a.type, a.metavar, a.default) == (b.name, b.type, b.metavar, b.default)
        assert a.name == dest and a.default is None
        assert a.help == "With --height: " + b.help[0].lower() + b.help[1:]
        assert not b.help.startswith("With") and unit in b.help
    for opt in ("--max-diameter", "--min-fill"):
        assert "[default: the map's" in inverse[opt].help
    for name in ("place", "inverse"):
        out = CliRunner().invoke(cli, [name, "--help"]).output
        assert "target boundary radius r_a" in out.lower() and "--min-fill P" in out
