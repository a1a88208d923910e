"""Composition: a node definition's base, mixins and main merged into one interface."""

from nodl.composition.compose import ComposedNode, compose, compose_report
from nodl.composition.layers import Layer
from nodl.composition.resolvers import (
    ResolutionError,
    ResolveContext,
    Resolved,
    Resolver,
    load_resolvers,
)

__all__ = ['ComposedNode', 'Layer', 'ResolutionError', 'ResolveContext', 'Resolved', 'Resolver',
           'compose', 'compose_report', 'load_resolvers']
