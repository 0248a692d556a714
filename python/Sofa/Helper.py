"""Sofa.Helper: SOFA's messages (msg_info, msg_warning, msg_error, msg_deprecated, msg_fatal),
printed to standard error as SOFA prints them: ``[INFO]    [emitter] message``."""

import sys


def _message(kind, args):
    if len(args) >= 2:
        emitter = args[0].getName() if hasattr(args[0], "getName") else str(args[0])
        text = " ".join(str(a) for a in args[1:])
    else:
        emitter, text = "PythonScript", " ".join(str(a) for a in args)
    print(f"[{kind}]".ljust(10) + f" [{emitter}] {text}", file=sys.stderr)


def msg_info(*args):
    _message("INFO", args)


def msg_warning(*args):
    _message("WARNING", args)


def msg_error(*args):
    _message("ERROR", args)


def msg_deprecated(*args):
    _message("DEPRECATED", args)


def msg_fatal(*args):
    _message("FATAL", args)
