"""The policy model: one table of permissions; nothing else can be granted."""

import pytest

from nodl.composition.entities import EntityKind
from nodl.policy.model import ACCESS_OF_KIND, PERMISSIONS, Grant, Policy, Profile, Source, permission_list


def test_every_endpoint_kind_has_its_access():
    assert ACCESS_OF_KIND == {
        'publisher': ('topic', 'publish'), 'subscription': ('topic', 'subscribe'),
        'service_server': ('service', 'reply'), 'service_client': ('service', 'request'),
        'action_server': ('action', 'execute'), 'action_client': ('action', 'call')}
    assert {k for k in ACCESS_OF_KIND} == {k.value for k in EntityKind if k.communication}


def test_unknown_permission_kinds_are_refused():
    with pytest.raises(ValueError, match='unknown permission kind'):
        permission_list('parameters')
    with pytest.raises(ValueError, match="unknown topics permission 'execute'"):
        Grant('topic', 'execute', '/x')
    assert [p.element for p in PERMISSIONS] == ['actions', 'services', 'topics']


def test_profile_grants_merge_sources_and_sort():
    profile = Profile('/robot', 'driver')
    profile.grant('topic', 'subscribe', '/b', Source('a'))
    profile.grant('topic', 'publish', '/z', Source('b'))
    profile.grant('topic', 'publish', '/z', Source('c'))
    profile.grant('action', 'call', '/n')
    assert profile.fqn == '/robot/driver'
    assert [(g.access, g.name) for g in profile.sorted_grants()] == [
        ('call', '/n'), ('publish', '/z'), ('subscribe', '/b')]
    assert [s.what for s in profile.grants[('topic', 'publish', '/z')].sources] == ['b', 'c']


def test_policy_orders_enclaves_and_profiles():
    policy = Policy()
    policy.enclave('/z').profiles.append(Profile('/', 'b'))
    policy.enclave('/a').profiles += [Profile('/x', 'a'), Profile('/', 'c')]
    assert [(e.path, p.fqn) for e, p in policy.profiles()] == [('/a', '/c'), ('/a', '/x/a'), ('/z', '/b')]
    assert policy.profile('/x/a') is not None and policy.profile('/nope') is None
