"""Errors that users cause, reported as one line."""


class InputError(Exception):
    """Bad input: a model, plan, formula or question that cannot be used.

    The message is one line saying what is wrong and where; the command line
    prints it and exits with code 2.
    """
