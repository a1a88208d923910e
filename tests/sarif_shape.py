"""The shape of a SARIF 2.1.0 log, as the OASIS standard defines it, for tests.

Written from the standard (SARIF 2.1.0, OASIS, with its errata), not copied from
its JSON schema: every object a toolkit log may hold is checked for its
required properties, the types and ranges of the properties it uses, and no
property the standard does not define for that object (the schema sets
``additionalProperties: false`` on each of them).  The objects the toolkit
never writes (code flows, fixes, graphs, ...) are refused, so a new use of
them has to be added here deliberately.
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ['assert_sarif_2_1_0']

#: object -> (required properties, allowed properties) for the objects a toolkit log holds.
_OBJECTS: dict[str, tuple[set[str], set[str]]] = {
    'log': ({'version', 'runs'}, {'$schema', 'version', 'runs', 'inlineExternalProperties',
                                  'properties'}),
    'run': ({'tool'}, {'tool', 'invocations', 'conversion', 'language', 'versionControlProvenance',
                       'originalUriBaseIds', 'artifacts', 'logicalLocations', 'graphs', 'results',
                       'automationDetails', 'runAggregates', 'baselineGuid', 'redactionTokens',
                       'defaultEncoding', 'defaultSourceLanguage', 'newlineSequences', 'columnKind',
                       'externalPropertyFileReferences', 'threadFlowLocations', 'taxonomies',
                       'addresses', 'translations', 'policies', 'webRequests', 'webResponses',
                       'specialLocations', 'properties'}),
    'tool': ({'driver'}, {'driver', 'extensions', 'properties'}),
    'toolComponent': ({'name'}, {'guid', 'name', 'organization', 'product', 'productSuite',
                                 'shortDescription', 'fullDescription', 'fullName', 'version',
                                 'semanticVersion', 'dottedQuadFileVersion', 'releaseDateUtc',
                                 'downloadUri', 'informationUri', 'globalMessageStrings',
                                 'notifications', 'rules', 'taxa', 'locations', 'language',
                                 'contents', 'isComprehensive', 'localizedDataSemanticVersion',
                                 'minimumRequiredLocalizedDataSemanticVersion',
                                 'associatedComponent', 'translationMetadata',
                                 'supportedTaxonomies', 'properties'}),
    'reportingDescriptor': ({'id'}, {'id', 'deprecatedIds', 'guid', 'deprecatedGuids', 'name',
                                     'deprecatedNames', 'shortDescription', 'fullDescription',
                                     'messageStrings', 'defaultConfiguration', 'helpUri', 'help',
                                     'relationships', 'properties'}),
    'reportingConfiguration': (set(), {'enabled', 'level', 'rank', 'parameters', 'properties'}),
    'multiformatMessageString': ({'text'}, {'text', 'markdown', 'properties'}),
    'message': (set(), {'text', 'markdown', 'id', 'arguments', 'properties'}),
    'result': ({'message'}, {'ruleId', 'ruleIndex', 'rule', 'kind', 'level', 'message',
                             'analysisTarget', 'locations', 'guid', 'correlationGuid',
                             'occurrenceCount', 'partialFingerprints', 'fingerprints', 'stacks',
                             'codeFlows', 'graphs', 'graphTraversals', 'relatedLocations',
                             'suppressions', 'baselineState', 'rank', 'attachments', 'hostedViewerUri',
                             'workItemUris', 'provenance', 'fixes', 'taxa', 'webRequest',
                             'webResponse', 'properties'}),
    'location': (set(), {'id', 'physicalLocation', 'logicalLocations', 'message', 'annotations',
                         'relationships', 'properties'}),
    'physicalLocation': (set(), {'address', 'artifactLocation', 'region', 'contextRegion',
                                 'properties'}),
    'artifactLocation': (set(), {'uri', 'uriBaseId', 'index', 'description', 'properties'}),
    'region': (set(), {'startLine', 'startColumn', 'endLine', 'endColumn', 'charOffset',
                       'charLength', 'byteOffset', 'byteLength', 'snippet', 'message',
                       'sourceLanguage', 'properties'}),
    'logicalLocation': (set(), {'name', 'index', 'fullyQualifiedName', 'decoratedName',
                                'parentIndex', 'kind', 'properties'}),
}

#: What a toolkit log may use of the objects above; anything else fails (see the module doc).
_USED = {
    'run': {'tool', 'originalUriBaseIds', 'results', 'invocations', 'properties'},
    'result': {'ruleId', 'ruleIndex', 'level', 'message', 'locations', 'relatedLocations', 'kind',
               'properties'},
}

_LEVELS = {'none', 'note', 'warning', 'error'}
_URI_REFERENCE = re.compile(r"[A-Za-z0-9\-._~:/?#\[\]@!$&'()*+,;=%]*")


def _object(value: Any, kind: str, where: str) -> dict[str, Any]:
    assert isinstance(value, dict), f'{where}: a {kind} object must be a JSON object'
    required, allowed = _OBJECTS[kind]
    missing = required - set(value)
    assert not missing, f'{where}: {kind} lacks {sorted(missing)}'
    unknown = set(value) - allowed
    assert not unknown, f'{where}: {kind} has properties SARIF 2.1.0 does not define: {sorted(unknown)}'
    unused = set(value) - _USED.get(kind, allowed)
    assert not unused, f'{where}: {kind} uses {sorted(unused)}: add them to tests/sarif_shape.py'
    return value


def _integer(value: Any, minimum: int, where: str) -> None:
    assert isinstance(value, int) and not isinstance(value, bool) and value >= minimum, \
        f'{where}: expected an integer >= {minimum}, got {value!r}'


def _string(value: Any, where: str) -> str:
    assert isinstance(value, str), f'{where}: expected a string, got {value!r}'
    return value


def _uri(value: Any, where: str, absolute: bool = False) -> None:
    text = _string(value, where)
    assert _URI_REFERENCE.fullmatch(text), f'{where}: {text!r} is not a URI reference (escape it)'
    if absolute:
        assert re.match(r'[A-Za-z][A-Za-z0-9+.-]*:', text), f'{where}: {text!r} is not absolute'


def _message(value: Any, kind: str, where: str) -> None:
    message = _object(value, kind, where)
    if kind == 'message':
        assert 'text' in message or 'id' in message, f'{where}: a message needs text or id'
    if 'text' in message:
        assert _string(message['text'], where + '.text'), f'{where}: empty text'


def _artifact_location(value: Any, where: str, base_ids: set[str]) -> None:
    artifact = _object(value, 'artifactLocation', where)
    if 'uri' in artifact:
        # a relative uri needs a base it is relative to; an absolute one has none
        _uri(artifact['uri'], where + '.uri', absolute='uriBaseId' not in artifact)
    if 'uriBaseId' in artifact:
        assert artifact['uriBaseId'] in base_ids, f'{where}: unknown uriBaseId {artifact["uriBaseId"]!r}'
    if 'index' in artifact:
        _integer(artifact['index'], -1, where + '.index')


def _location(value: Any, where: str, base_ids: set[str]) -> None:
    location = _object(value, 'location', where)
    if 'id' in location:
        _integer(location['id'], -1, where + '.id')
    if 'physicalLocation' in location:
        physical = _object(location['physicalLocation'], 'physicalLocation', where + '.physicalLocation')
        assert 'artifactLocation' in physical or 'address' in physical, \
            f'{where}: a physicalLocation needs an artifactLocation or an address'
        _artifact_location(physical['artifactLocation'], where + '.artifactLocation', base_ids)
        if 'region' in physical:
            region = _object(physical['region'], 'region', where + '.region')
            for key in ('startLine', 'startColumn', 'endLine', 'endColumn'):
                if key in region:
                    _integer(region[key], 1, f'{where}.region.{key}')
            assert {'startLine', 'charOffset', 'byteOffset'} & set(region), \
                f'{where}: a region needs startLine, charOffset or byteOffset'
    for index, logical in enumerate(location.get('logicalLocations', [])):
        found = _object(logical, 'logicalLocation', f'{where}.logicalLocations[{index}]')
        assert found, f'{where}: an empty logicalLocation'
    if 'message' in location:
        _message(location['message'], 'message', where + '.message')


def assert_sarif_2_1_0(log: Any) -> None:
    """Fail (AssertionError saying where and what) unless ``log`` is a SARIF 2.1.0 log of the
    kind the toolkit writes: one rule per code, each result pointing at its rule."""
    _object(log, 'log', 'log')
    assert log['version'] == '2.1.0', log['version']
    if '$schema' in log:
        _uri(log['$schema'], 'log.$schema', absolute=True)
    assert isinstance(log['runs'], list) and log['runs'], 'log.runs: expected runs'
    for r, run in enumerate(log['runs']):
        where = f'runs[{r}]'
        _object(run, 'run', where)
        driver = _object(_object(run['tool'], 'tool', where + '.tool')['driver'], 'toolComponent',
                         where + '.tool.driver')
        _string(driver['name'], where + '.driver.name')
        if 'informationUri' in driver:
            _uri(driver['informationUri'], where + '.driver.informationUri', absolute=True)
        rules = driver.get('rules', [])
        ids = []
        for i, rule in enumerate(rules):
            rule_where = f'{where}.rules[{i}]'
            _object(rule, 'reportingDescriptor', rule_where)
            ids.append(_string(rule['id'], rule_where + '.id'))
            if 'shortDescription' in rule:
                _message(rule['shortDescription'], 'multiformatMessageString', rule_where)
            if 'helpUri' in rule:
                _uri(rule['helpUri'], rule_where + '.helpUri', absolute=True)
            if 'defaultConfiguration' in rule:
                configuration = _object(rule['defaultConfiguration'], 'reportingConfiguration',
                                        rule_where + '.defaultConfiguration')
                assert configuration.get('level', 'warning') in _LEVELS, rule_where
        assert len(ids) == len(set(ids)), f'{where}: one rule per code, got {ids}'
        bases = run.get('originalUriBaseIds', {})
        assert isinstance(bases, dict), where
        for name, base in bases.items():
            _artifact_location(base, f'{where}.originalUriBaseIds.{name}', set())
            assert base['uri'].endswith('/'), f'{where}: a base URI must end with /'
        for n, result in enumerate(run.get('results', [])):
            result_where = f'{where}.results[{n}]'
            _object(result, 'result', result_where)
            _message(result['message'], 'message', result_where + '.message')
            assert result.get('level', 'warning') in _LEVELS, result_where
            if 'ruleIndex' in result:
                _integer(result['ruleIndex'], -1, result_where + '.ruleIndex')
                assert result['ruleIndex'] < len(ids), f'{result_where}: no rule {result["ruleIndex"]}'
                assert ids[result['ruleIndex']] == result.get('ruleId'), result_where
            if 'ruleId' in result:
                assert result['ruleId'] in ids, f'{result_where}: no rule {result["ruleId"]}'
            for key in ('locations', 'relatedLocations'):
                for i, location in enumerate(result.get(key, [])):
                    _location(location, f'{result_where}.{key}[{i}]', set(bases))
