"""Reasons: sufficient and necessary reasons for verdicts, and their words.

``DEFAULT_LIMIT`` is here, in the package's light module, so that the command
line can show it in its help without loading clingo's reasoning modules.
"""

# At most this many sufficient and this many necessary reasons per judgement.
DEFAULT_LIMIT = 10
