"""The document model: typed classes for the three kinds of NoDL document."""

from nodl_schema.model.interface import (
    ENDPOINT_SECTIONS, ActionEndpoint, Endpoint, Interface, ServiceEndpoint, TopicEndpoint)
from nodl_schema.model.node import Base, Mixin, Node
from nodl_schema.model.parameter import ParameterDefinition
from nodl_schema.model.qos import QOS_POLICIES, QoSProfile

__all__ = [
    'ENDPOINT_SECTIONS', 'ActionEndpoint', 'Base', 'Endpoint', 'Interface', 'Mixin', 'Node',
    'ParameterDefinition', 'QOS_POLICIES', 'QoSProfile', 'ServiceEndpoint', 'TopicEndpoint',
]
