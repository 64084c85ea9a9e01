"""Generic numerics that every analysis may use: root bracketing and a seeded multi-start.

Nothing here knows about hexapods: :mod:`.bracketing` finds the first sign change of
many scalar functions along a line at once; :mod:`.multistart` maximizes one coordinate
under constraints from several starts.
"""

from hexaleg.numerics.bracketing import anderson_bjorck, first_crossings
from hexaleg.numerics.multistart import box_starts, maximize_coordinate

__all__ = ["anderson_bjorck", "box_starts", "first_crossings", "maximize_coordinate"]
