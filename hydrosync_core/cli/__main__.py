import sys

from hydrosync_core.cli import main

sys.exit(main())
