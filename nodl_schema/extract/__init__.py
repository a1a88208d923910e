"""Extracting a node's interface from its source code (``nodl extract``).

* :mod:`~nodl_schema.extract.model`: what is found (nodes, entities, locations, gaps);
* :mod:`~nodl_schema.extract.writer`: a found node as a draft NoDL definition;
* :mod:`~nodl_schema.extract.python`: the rclpy extractor (Python's ``ast``, nothing run);
* :mod:`~nodl_schema.extract.targets`: packages and executables (setup.py, setup.cfg, and a
  hook for other build files);
* :mod:`~nodl_schema.extract.diff`: comparing an extraction with a definition.
"""
