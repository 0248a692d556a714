"""The codes (ord) of the keys Key names: ``KeyCode.uparrow == 19``, ``KeyCode.A == 65``."""

from . import Key as _Key

for _name in dir(_Key):
    if not _name.startswith("_") and not _name.startswith("KP_"):
        globals()[_name] = ord(getattr(_Key, _name))
del _name
