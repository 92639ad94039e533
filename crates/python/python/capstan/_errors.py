"""The exceptions of capstan: what went wrong, as the command line's exit codes tell it."""


class CapstanError(Exception):
    """Base class of every error capstan raises (besides KeyboardInterrupt)."""


class InvalidInputError(CapstanError, ValueError):
    """Bad input (exit code 2): the message names the key, the value and the allowed range."""


class NoEquilibriumError(CapstanError):
    """No static equilibrium (exit code 3), e.g. a tension ratio beyond what friction holds."""


class NotConvergedError(CapstanError):
    """A solver did not converge (exit code 4)."""
