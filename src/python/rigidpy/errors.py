"""The error of bad input (a missing or malformed file, an unknown object, a bad option): the
commands print it as one line `rigid: error: ...` and exit with status 2."""


class InputError(Exception):
    pass
