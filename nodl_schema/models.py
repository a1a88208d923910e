"""The reference API's document models: pydantic models (pydantic's version 1 API).

The classes, fields, aliases and enums are those of the reference
implementation's ``nodl_schema.models`` (``NodlDocument.parse_obj(data)``,
``doc.json(exclude_none=True)``, ``TopicEndpoint(name=..., type=..., qos=...)``,
``History.KEEP_LAST``, ...), so programs written against it run unchanged.
They need pydantic (1.10.17 or later, or 2.x, whose ``pydantic.v1`` they use):
``pip install 'nodl-toolkit[reference]'``.

:func:`to_toolkit` and :func:`from_toolkit` map a document to and from the
toolkit's own model (:class:`nodl.model.Interface`).
"""

from __future__ import annotations

import enum
import re
from typing import Any

try:
    from pydantic.v1 import BaseModel, Extra, Field, validator
except ImportError:  # pragma: no cover - the message is tested in a process without pydantic
    raise ImportError("nodl_schema.models needs pydantic: pip install 'nodl-toolkit[reference]' "
                      "(or pip install 'pydantic>=1.10.17')") from None

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nodl.model import Interface

__all__ = ['ScalarType', 'ArrayType', 'Reference', 'History', 'Reliability', 'Durability',
           'Liveliness', 'QosProfile', 'TopicEndpoint', 'ServiceEndpoint', 'ActionEndpoint',
           'Validation', 'ParameterDefinition', 'NodlDocument', 'to_toolkit', 'from_toolkit']

# The shapes the reference's schema gives (its models check them too).
_URI = r'^[a-z][a-z0-9+.-]*://[^\s/][^\s]*$'
_NAME = r'^[A-Za-z]$|^[/~A-Za-z][A-Za-z0-9_/]*[A-Za-z0-9_]$'
_TYPE = r'^[a-zA-Z][a-zA-Z0-9_]*(/(msg|srv|action))?/[A-Z][a-zA-Z0-9]*$'
_FIXED = re.compile(r'(string|int_array|double_array|string_array)_fixed_[1-9][0-9]*')


class _Strict(BaseModel):
    class Config:
        extra = Extra.forbid


class ScalarType(enum.Enum):
    """A scalar parameter type."""

    bool = 'bool'
    int = 'int'
    double = 'double'
    string = 'string'
    none = 'none'


class ArrayType(enum.Enum):
    """An array parameter type."""

    bool_array = 'bool_array'
    byte_array = 'byte_array'
    int_array = 'int_array'
    double_array = 'double_array'
    string_array = 'string_array'


class History(enum.Enum):
    """QoS history policy."""

    KEEP_LAST = 'KEEP_LAST'
    KEEP_ALL = 'KEEP_ALL'
    SYSTEM_DEFAULT = 'SYSTEM_DEFAULT'


class Reliability(enum.Enum):
    """QoS reliability policy."""

    RELIABLE = 'RELIABLE'
    BEST_EFFORT = 'BEST_EFFORT'
    SYSTEM_DEFAULT = 'SYSTEM_DEFAULT'
    BEST_AVAILABLE = 'BEST_AVAILABLE'


class Durability(enum.Enum):
    """QoS durability policy."""

    TRANSIENT_LOCAL = 'TRANSIENT_LOCAL'
    VOLATILE = 'VOLATILE'
    SYSTEM_DEFAULT = 'SYSTEM_DEFAULT'
    BEST_AVAILABLE = 'BEST_AVAILABLE'


class Liveliness(enum.Enum):
    """QoS liveliness policy."""

    AUTOMATIC = 'AUTOMATIC'
    MANUAL_BY_TOPIC = 'MANUAL_BY_TOPIC'
    SYSTEM_DEFAULT = 'SYSTEM_DEFAULT'
    BEST_AVAILABLE = 'BEST_AVAILABLE'


class Reference(_Strict):
    """An ``include`` entry: the URI of another document."""

    ref: str = Field(..., regex=_URI, description='<scheme>://<body>: nodl://PACKAGE/NAME, '
                     'local://PATH, or a scheme a registered resolver handles.')


class QosProfile(_Strict):
    """QoS settings; durations in nanoseconds."""

    history: History
    depth: int | None = Field(None, ge=1, description='Queue depth (with KEEP_LAST).')
    reliability: Reliability
    durability: Durability | None = None
    deadline_ns: int | None = Field(None, ge=0)
    lifespan_ns: int | None = Field(None, ge=0)
    liveliness: Liveliness | None = None
    liveliness_lease_duration_ns: int | None = Field(None, ge=0)


class TopicEndpoint(_Strict):
    """A publisher or subscription."""

    name: str = Field(..., regex=_NAME)
    type: str = Field(..., regex=_TYPE)
    qos: QosProfile
    description: str | None = None


class ServiceEndpoint(_Strict):
    """A service server or client (one QoS profile for both directions)."""

    name: str = Field(..., regex=_NAME)
    type: str = Field(..., regex=_TYPE)
    qos: QosProfile | None = None
    description: str | None = None


class ActionEndpoint(_Strict):
    """An action server or client."""

    name: str = Field(..., regex=_NAME)
    type: str = Field(..., regex=_TYPE)
    description: str | None = None


_Numbers = list[float] | None
_Comparison = list[float] | float | None
_Size = list[int] | int | None


class Validation(_Strict):
    """A parameter's validators; ``name<>`` keys are fields ``name__`` (given by alias)."""

    bounds__: _Numbers = Field(None, alias='bounds<>')
    lt__: _Comparison = Field(None, alias='lt<>')
    gt__: _Comparison = Field(None, alias='gt<>')
    lt_eq__: _Comparison = Field(None, alias='lt_eq<>')
    gt_eq__: _Comparison = Field(None, alias='gt_eq<>')
    one_of__: list[list[Any]] | None = Field(None, alias='one_of<>')
    bounds: _Numbers = None
    lt: _Comparison = None
    gt: _Comparison = None
    lt_eq: _Comparison = None
    gt_eq: _Comparison = None
    one_of: list[list[Any]] | None = None
    not_empty__: list[Any] | None = Field(None, alias='not_empty<>')
    not_empty: list[Any] | None = None
    fixed_size__: _Size = Field(None, alias='fixed_size<>')
    size_gt__: _Size = Field(None, alias='size_gt<>')
    size_lt__: _Size = Field(None, alias='size_lt<>')
    fixed_size: _Size = None
    size_gt: _Size = None
    size_lt: _Size = None
    unique__: list[Any] | None = Field(None, alias='unique<>')
    subset_of__: list[list[Any]] | None = Field(None, alias='subset_of<>')
    element_bounds__: _Numbers = Field(None, alias='element_bounds<>')
    lower_element_bounds__: _Comparison = Field(None, alias='lower_element_bounds<>')
    upper_element_bounds__: _Comparison = Field(None, alias='upper_element_bounds<>')
    unique: list[Any] | None = None
    subset_of: list[list[Any]] | None = None
    element_bounds: _Numbers = None
    lower_element_bounds: _Comparison = None
    upper_element_bounds: _Comparison = None

    @validator('fixed_size__', 'size_gt__', 'size_lt__', 'fixed_size', 'size_gt', 'size_lt')
    def _not_negative(cls, value: Any) -> Any:
        sizes = value if isinstance(value, list) else [value]
        if any(isinstance(size, int) and size < 0 for size in sizes):
            raise ValueError('a size is 0 or more')
        return value


class ParameterDefinition(_Strict):
    """A parameter: its type, default, description, whether it is read-only, and validators."""

    type: ScalarType | ArrayType | str
    default_value: Any | None = None
    description: str | None = ''
    read_only: bool | None = False
    additional_constraints: str | None = ''
    validation: Validation | None = None

    @validator('type')
    def _fixed_size_type(cls, value: Any) -> Any:
        if isinstance(value, str) and not _FIXED.fullmatch(value):
            raise ValueError(f'{value!r} is not a parameter type (a scalar, an array, or '
                             'string_fixed_N, int_array_fixed_N, double_array_fixed_N, '
                             'string_array_fixed_N)')
        return value


class NodlDocument(_Strict):
    """A NoDL document: one node's interface, and the documents it includes."""

    nodl_version: int = Field(2, const=True)
    description: str | None = None
    codegen: dict[str, dict[str, Any]] | None = None
    include: list[Reference] | None = None
    parameters: dict[str, ParameterDefinition] | None = None
    publishers: list[TopicEndpoint] | None = None
    subscriptions: list[TopicEndpoint] | None = None
    service_servers: list[ServiceEndpoint] | None = None
    service_clients: list[ServiceEndpoint] | None = None
    action_servers: list[ActionEndpoint] | None = None
    action_clients: list[ActionEndpoint] | None = None


def _data(doc: NodlDocument) -> dict[str, Any]:
    import json

    data: dict[str, Any] = json.loads(doc.json(exclude_none=True, by_alias=True))
    return data


def to_toolkit(doc: NodlDocument) -> Interface:
    """The document as the toolkit's interface definition (:class:`nodl.model.Interface`).

    A document with ``include`` is refused (:class:`ValueError`): merge it first
    (:func:`nodl_schema.load_nodl` does).  The result is validated by the toolkit.
    """
    from nodl.loading import model_from_data
    from nodl.model import Interface

    if doc.include:
        raise ValueError('a document with include is not an interface definition: resolve and '
                         'merge its includes first (nodl_schema.load_nodl)')
    data = _data(doc)
    data.pop('include', None)
    model = model_from_data(data)
    if not isinstance(model, Interface):
        raise ValueError(f'the document reads as {type(model).__name__}, not an Interface')
    return model


def from_toolkit(interface: Interface) -> NodlDocument:
    """The toolkit's interface definition as a :class:`NodlDocument`."""
    result: NodlDocument = NodlDocument.parse_obj(interface.to_dict())
    return result
