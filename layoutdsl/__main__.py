import sys

from layoutdsl.cli import main

sys.exit(main())
