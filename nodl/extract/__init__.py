"""Extracting a node's interface from its source code (``nodl extract``).

* :mod:`~nodl.extract.model`: what is found (nodes, entities, locations, gaps);
* :mod:`~nodl.extract.writer`: a found node as a draft NoDL definition;
* :mod:`~nodl.extract.python`: the rclpy extractor (Python's ``ast``, nothing run);
* :mod:`~nodl.extract.targets`: packages and executables (setup.py, setup.cfg, and a
  hook for other build files);
* :mod:`~nodl.extract.diff`: comparing an extraction with a definition.
"""
