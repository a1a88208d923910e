"""What ``nodl extract`` finds in source code: nodes, their entities, where each was found,
and the gaps (what the source does not fix before it runs).

The model is language-neutral: the Python (rclpy) and C++ (rclcpp) extractors both fill it,
and the writer (:mod:`nodl.extract.writer`) and the comparison
(:mod:`nodl.extract.diff`) read it.  Nothing here is guessed: a value the source
computes at run time is ``None`` and the entity carries a :class:`Gap` that says what is
missing and where.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.location import Location

if TYPE_CHECKING:
    from typing import Any

    from nodl.model.qos import QoSProfile

__all__ = ['Gap', 'ExtractedEntity', 'ExtractedNode', 'Extraction', 'PARAMETERS',
           'ENTITY_SECTIONS']

#: The section of a parameter entity (endpoints use the endpoint section keys of
#: :data:`nodl.vocabulary.SECTIONS`: ``publishers``, ``subscriptions``...).
PARAMETERS = 'parameters'


def _sections() -> tuple[str, ...]:
    from nodl.vocabulary import SECTION_KEYS

    return (PARAMETERS, *SECTION_KEYS)


#: Every section an entity can belong to, in file order.
ENTITY_SECTIONS: tuple[str, ...] = _sections()


@dataclass(frozen=True, slots=True)
class Gap:
    """Something the source does not fix before it runs: an entity's name, type, QoS, default...

    ``what`` names the missing field (``name``, ``type``, ``qos``, ``default_value``,
    ``entity`` for an entity whose very existence depends on a plug-in); ``reason`` is the
    sentence a user reads (``topic name is computed at run time``); ``code`` the diagnostic
    code (NODL9xx).
    """

    what: str
    reason: str
    location: Location
    code: str
    severity: Severity = Severity.WARNING

    def diagnostic(self) -> Diagnostic:
        """The located diagnostic of this gap."""
        return Diagnostic(self.severity, self.reason,
                          file=self.location.file, line=self.location.line,
                          column=self.location.column, code=self.code)


@dataclass(slots=True)
class ExtractedEntity:
    """One parameter or endpoint found in the source.

    * ``section``: ``parameters`` or an endpoint section key (``publishers``...);
    * ``name``: as the node creates it (``chatter``, ``~/cmd``, ``pid.kp``); None when computed;
    * ``type``: the interface type (``std_msgs/msg/String``) or, for a parameter, its NoDL type
      (``double``, ``string_array``); None when unknown;
    * ``qos``: a topic's profile (policies expanded; None when unknown or for services);
    * ``default_value`` / ``has_default``: a parameter's default (``has_default`` False: none is
      given, the node must be started with it);
    * ``read_only``, ``validation``, ``description``: from a parameter's descriptor;
    * ``helper``: the helper that creates it (``tf2_ros.TransformListener``), None when direct;
    * ``gaps``: what is missing (a gap on ``name``, ``type`` or ``qos`` makes the entity a draft
      the writer comments out).
    """

    section: str
    name: str | None
    type: str | None
    location: Location
    qos: QoSProfile | None = None
    default_value: Any = None
    has_default: bool = False
    read_only: bool = False
    validation: dict[str, Any] | None = None
    description: str | None = None
    helper: str | None = None
    gaps: list[Gap] = field(default_factory=list)

    @property
    def is_parameter(self) -> bool:
        """Whether the entity is a parameter (not an endpoint)."""
        return self.section == PARAMETERS

    @property
    def complete(self) -> bool:
        """Whether the entity can be written as it is (no gap)."""
        return not self.gaps

    def key(self) -> tuple[str, str | None]:
        """``(section, name)``: what identifies the entity in a definition."""
        return (self.section, self.name)


@dataclass(slots=True)
class ExtractedNode:
    """One node found in the source: a node class, or a node made in a function.

    ``package`` / ``executable`` come from the package's build files (setup.py or setup.cfg
    entry points, CMakeLists.txt); None when nothing maps the code to an executable (the writer
    then names the output after ``name``).  ``node_name`` is the ROS name the node is created
    with, when it is a constant.  ``base`` is ``node`` or ``lifecycle_node``.
    """

    name: str
    location: Location
    language: str
    base: str = 'node'
    package: str | None = None
    executable: str | None = None
    node_name: str | None = None
    entities: list[ExtractedEntity] = field(default_factory=list)
    #: Diagnostics about the node as a whole (the executable is unknown, a base is not resolved).
    notes: list[Diagnostic] = field(default_factory=list)
    #: Every source file read for this node (its module, its helpers' modules).
    sources: list[str] = field(default_factory=list)
    #: ``class``: a node class (instances made elsewhere); ``call``: a node object made by a call
    #: (``Node('talker')`` in a function or at module level).
    made_by: str = 'class'
    #: For a node made by a call: the top-level function it is made in (``''``: module level).
    made_in: str | None = None
    #: For a component (an rclcpp class registered as a plugin): its class, ``pkg::Class``.
    plugin: str | None = None

    def section(self, key: str) -> list[ExtractedEntity]:
        """The entities of one section, in source order."""
        return [e for e in self.entities if e.section == key]

    @property
    def gaps(self) -> list[Gap]:
        """Every gap of every entity."""
        return [g for e in self.entities for g in e.gaps]

    @property
    def diagnostics(self) -> list[Diagnostic]:
        """The node's notes and the diagnostics of its gaps, in source order."""
        found = list(self.notes) + [g.diagnostic() for g in self.gaps]
        found.sort(key=lambda d: (d.file, d.line, d.column))
        return found

    @property
    def output_name(self) -> str:
        """The name of its draft definition file, without ``.nodl.yaml``: the executable; for a
        C++ class no executable runs (a component), its registration key (the class in snake
        case, as ``nodl describe`` names composable nodes); else the node's name."""
        if self.executable:
            return self.executable
        name = self.plugin or self.name
        if '::' in name:
            from nodl.registry.node_info import plugin_key

            return plugin_key(name)
        return name


@dataclass(slots=True)
class Extraction:
    """What one extraction found: nodes, and diagnostics about the input as a whole
    (unparseable files, files too large, generated code, paths that cannot be read)."""

    nodes: list[ExtractedNode] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    #: Every source file read.
    files: list[str] = field(default_factory=list)
    #: file -> top-level function -> the names it calls (``Talker`` in ``node = Talker()``): which
    #: node classes an entry point's function starts.
    starts: dict[str, dict[str, list[str]]] = field(default_factory=dict)

    @property
    def all_diagnostics(self) -> list[Diagnostic]:
        """The input's diagnostics, then each node's, in order."""
        out = list(self.diagnostics)
        for node in self.nodes:
            out += node.diagnostics
        return out

    def extend(self, other: Extraction) -> None:
        """Add another extraction's nodes, diagnostics and files to this one."""
        self.nodes += other.nodes
        self.diagnostics += other.diagnostics
        self.files += [f for f in other.files if f not in self.files]
        self.starts.update(other.starts)
