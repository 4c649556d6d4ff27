"""``python -m rotorsim.cli``: the rotorsim command line."""

from rotorsim.cli.main import main

raise SystemExit(main())
