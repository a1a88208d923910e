"""The composer: a launch file as a composition of nodes, edited and checked (``nodl system``).

A shared layer: ``nodl system`` (the command line) and ``nodl studio`` (the web application)
both drive it.  Everything it returns is JSON-ready through ``to_dict()``.

Opening, making, saving::

    from nodl.composer import Composition
    c = Composition.open('rover.launch.xml', definitions=folders)   # or Composition.new(path)
    c.add('rover_sensors', 'lidar_driver', 'lidar', namespace='rover')
    c.connect('/rover/lidar:scan', '/rover/safety_controller:scan')  # -> Change
    c.set_parameter('/rover/lidar', 'scan_rate', '10.0')             # -> Change
    c.rename('/rover/lidar', 'front_lidar', None)                    # -> Change
    c.set_remaps('/rover/front_lidar', [('scan', 'front/scan')])     # -> Change
    c.analyse().findings          # nodl analyse's findings, same codes
    c.save()                      # -> list of diagnostics (empty: saved)

What the studio needs to know:

* **Ids.**  Every node has an id (``n3``) and every group one (``g2``), stable for the
  life of the :class:`Composition` (kept across :meth:`~Composition.save`).  Every operation
  that names a node takes its id, its final name (``/rover/lidar``), or its name when unique.
  Ports are named ``NODE:ENDPOINT``; ``ENDPOINT`` is the declared name (``scan``, ``~/status``),
  the final name, or ``KIND/NAME`` (``publisher/scan``) when a node has two of that name.
* **Operations never raise for a user's mistake**: they return a :class:`Change` whose
  ``diagnostics`` say what is wrong (an error means nothing changed) and ``ok``.  Only
  :meth:`Composition.open`/:meth:`Composition.new` raise :class:`ComposerError` (carrying
  one diagnostic) for a file that cannot be read or must not be replaced.
* **Cheap and dear calls.**  :meth:`~Composition.can_connect` is cheap (the last analysis's
  ports; call it while dragging).  :meth:`~Composition.analyse` runs ``nodl analyse``'s
  analysis once per change (cached until the next change); :meth:`~Composition.to_dict`
  runs it unless ``analyse=False``.  A Python launch file is analysed by running it in the
  launch sandbox: give ``limits=LaunchLimits(execute=False)`` for ``--no-exec``, and
  :meth:`~Composition.set_limits` after the user's explicit action to run it; the composer
  itself only parses Python, it never runs it.
* **Read-only parts.**  A node whose entry is not declarative (a condition, substitutions in
  its package/name/namespace) has ``editable: false`` and ``read_only_reason``; kept pieces
  (includes, arguments, parameter files, Python code) are listed under ``kept`` with their
  line.  Their text is written back exactly as read.
* **Saving** writes the file in place, atomically, and refuses (NODL980) when the file
  changed on disk since it was read, unless ``force``.  Nothing else is written next to it
  (an unsaved composition is analysed through a hidden copy next to it, removed at once).

Modules: :mod:`~nodl.composer.model` (items), :mod:`~nodl.composer.xml_format`,
:mod:`~nodl.composer.yaml_format`, :mod:`~nodl.composer.python_format` (reading and writing
each format), :mod:`~nodl.composer.formats` (the three behind one interface),
:mod:`~nodl.composer.analysed` (the real analysis of a composition), :mod:`~nodl.composer.ports`
(endpoints and whether two can be joined), :mod:`~nodl.composer.connecting` (the rules
that join them), :mod:`~nodl.composer.setting` (parameter values checked against the plan),
:mod:`~nodl.composer.renaming` (names, namespaces and a node's own remapping rules),
:mod:`~nodl.composer.adding` (adding and removing nodes), :mod:`~nodl.composer.values`
(parameter values as each format spells them), :mod:`~nodl.composer.rendering` (the text of
a document, and where each node is in it), :mod:`~nodl.composer.convert` (another format),
:mod:`~nodl.composer.change` (what an operation answers), :mod:`~nodl.composer.composition`
(the class).
"""

from __future__ import annotations

from nodl.composer.change import Change, ComposerError
from nodl.composer.composition import Composition
from nodl.composer.model import ComposedNode, Group, Kept, Param, Remap
from nodl.composer.ports import Port, Verdict

__all__ = [
           'Change',
           'ComposedNode',
           'ComposerError',
           'Composition',
           'Group',
           'Kept',
           'Param',
           'Port',
           'Remap',
           'Verdict',
]
