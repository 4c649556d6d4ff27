"""``python -m rotorsim``: the rotorsim command line."""

from rotorsim.cli.main import main

raise SystemExit(main())
