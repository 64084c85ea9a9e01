"""What a design is measured for, and one measurement of it: the vocabulary shared above.

:mod:`.metrics` declares every metric once (name, unit, label, which way is better, what
measures it) and holds a design's values of them, one typed field each;
:mod:`.requirement_specs` declares every requirement once (the metric it bounds, its range,
option and table key), :mod:`.requirements` is a decision's requirements and their checks,
:mod:`.requirements_table` the commented table a new design file gets; :mod:`.evaluate`
measures a design under its :class:`~.evaluate.Conditions` (each analysis at most once) and
:mod:`.goal` pairs requirements with an objective. The study, the explorer, the report
and the command line all import them from here; this layer imports the analyses below it
and nothing above.
"""
