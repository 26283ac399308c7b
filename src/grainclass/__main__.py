from grainclass.cli import main

main()
