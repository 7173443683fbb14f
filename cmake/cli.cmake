# Filled in by the cli work (see issues).
