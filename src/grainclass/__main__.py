from grainclass.cli import cli

cli()
