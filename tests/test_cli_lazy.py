"""The command line imports only the module of the subcommand it runs."""

import argparse
import subprocess
import sys
from importlib import import_module

from velplan import cli


def test_subcommand_table_matches_what_the_modules_register():
    found = {}
    for name in cli.COMMANDS:
        parser = argparse.ArgumentParser()
        sub = parser.add_subparsers()
        import_module(f"velplan.cli.{name}").register(sub)
        found.update({command: name for command in sub.choices})
    assert found == cli.SUBCOMMANDS


def test_a_subcommand_imports_only_its_own_module():
    code = ("import sys; from velplan.cli import build_parser; build_parser(['info', 'shaper']); "
            "print(sorted(m for m in sys.modules if m.startswith('velplan.cli.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    loaded = eval(out)  # a list of module names printed by the child
    assert "velplan.cli.kinematics" in loaded
    assert not {"velplan.cli.note", "velplan.cli.sweep", "velplan.cli.sheet", "velplan.cli.centres"} & set(loaded)


def test_help_lists_every_subcommand(capsys):
    parser = cli.build_parser([])
    text = parser.format_help()
    for command in cli.SUBCOMMANDS:
        assert command in text


def test_version_imports_no_subcommand_and_no_numpy():
    code = ("import sys\nfrom velplan.cli import main\ntry:\n    main(['--version'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in sys.modules if m.startswith('velplan.cli.') or m == 'numpy'))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.splitlines()[0].startswith("velplan ")
    assert eval(run.stdout.splitlines()[-1]) == []
