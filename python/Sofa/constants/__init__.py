"""Sofa.constants: the keys a controller's onKeypressedEvent receives (event["key"], a one-character
string), as SofaPython3 names them: ``Key.uparrow``, ``Key.A`` ..., and their codes (``KeyCode``)."""

from . import Key, KeyCode  # noqa: F401

__all__ = ["Key", "KeyCode"]
