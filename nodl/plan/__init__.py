"""The parameter plan: a shared layer every consumer asks, owned by no feature.

* :mod:`nodl.plan.parameter_plan` -- the language-neutral plan of a node's
  parameters (types, ROS parameter types, descriptors, ranges, validators),
  derived once from the definition; the generators (Python, C++), the runtime
  (``NodlNode``), ``nodl params``, ``nodl new`` and ``nodl doc`` all read it.
* :mod:`nodl.plan.identifiers` -- names to identifiers of a target language,
  collision-free and keyword-free (the plan's struct fields, generated code,
  scaffolded packages).
* :mod:`nodl.plan.defaults_file` -- a node's parameter defaults as a ready
  ``ros__parameters`` file (``nodl params DEFINITION``, the packages ``nodl new`` writes).
"""
