"""The catalogue of diagnostic codes: every code the toolkit reports, once.

A code is stable: once released it keeps its meaning, so that users can look
it up, silence it (``--ignore``) or promote it (``--error``).  Codes are
grouped by the stage that reports them:

=========  ===============================================================
range      stage
=========  ===============================================================
NODL0xx    reading files: I/O, encodings, YAML/JSON/XML syntax, limits
NODL1xx    structure (the JSON Schemas): keys, types, required values
NODL2xx    semantic rules: ROS names, interface types, parameters,
           validators, QoS, duplicates, descriptions, references
NODL3xx    composition: bases, mixins, overrides, client libraries
NODL4xx    live: drift between a definition and a running node
NODL5xx    system analysis: launch files, instances, connections
NODL6xx    SROS 2 policies
NODL7xx    parameter files and code generation
NODL8xx    dialects and conversion: legacy XML, ``include``, generate_parameter_library
NODL9xx    extraction from source code (``nodl extract``, 901-969): gaps,
           unreadable sources, comparison with a definition (901-929 Python
           and the common frame, 930-959 C++, 960-969 across languages);
           the composer of launch files (``nodl system``, 970-989) and its
           web application (``nodl studio``, 990-999)
=========  ===============================================================

Each entry: code -> (default severity, one-line explanation).  A test keeps
this table and the code in step (every code used is listed here, and every
code listed here is used).
"""

from __future__ import annotations

from nodl.wording import close_matches

__all__ = ['CODES', 'RANGES', 'explain', 'default_severity', 'is_code', 'close_codes', 'catalogue_markdown']

#: The stage of each range of codes (``'1'`` covers NODL100-NODL199).
RANGES: dict[str, str] = {
    '0': 'Reading files: I/O, encodings, YAML/JSON/XML syntax, limits',
    '1': 'Structure (the JSON Schemas): keys, types, required values',
    '2': 'Semantic rules: ROS names, interface types, parameters, validators, duplicates, descriptions',
    '3': 'Composition: bases, mixins, overrides, client libraries',
    '4': 'Live: drift between a definition and a running node',
    '5': 'System analysis: launch files, instances, connections',
    '6': 'SROS 2 policies',
    '7': 'Parameter files and code generation',
    '8': 'Dialects and conversion: legacy XML, include, generate_parameter_library',
    '9': 'Extraction from source (NODL901-969) and the composer of launch files: nodl system (NODL970-989), nodl studio (NODL990-999)',
}

#: code -> (default severity, one-line explanation).
CODES: dict[str, tuple[str, str]] = {
    # -- NODL0xx: reading files --------------------------------------------
    'NODL001': ('error', 'the file is larger than the 10 MB limit'),
    'NODL002': ('error', 'the file is not UTF-8 text (another encoding, a byte or character that is not allowed)'),
    'NODL003': ('error', 'YAML or JSON syntax error'),
    'NODL004': ('error', 'a tab character is used for indentation; YAML allows only spaces'),
    'NODL005': ('error', 'the file holds more than one YAML document'),
    'NODL006': ('error', 'a mapping has the same key twice (YAML loaders would silently keep the last)'),
    'NODL007': ('error', 'a YAML anchor is defined twice'),
    'NODL008': ('error', 'YAML aliases are recursive or expand beyond 10,000 nodes ("billion laughs")'),
    'NODL009': ('error', 'the document nests deeper than 100 levels'),
    'NODL010': ('error', 'a YAML construct NoDL does not accept: a tag, a non-scalar key, a bad merge key'),
    'NODL011': ('error', 'the document is empty or is not a mapping'),
    'NODL012': ('error', 'XML syntax error'),
    'NODL013': ('error', 'an XML document type declaration or entity (not allowed: XML bombs)'),
    'NODL014': ('warning', 'the XML declaration names an encoding other than UTF-8'),
    'NODL015': ('error', 'a file the document refers to cannot be read'),
    'NODL016': ('error', 'JSON syntax error (in a file read as strict JSON)'),
    'NODL017': ('warning', 'a frontend plug-in (nodl.frontends) is broken and was skipped: it cannot be '
                'loaded, or it raised while reading; the other frontends read the file'),
    'NODL018': ('error', 'no frontend reads the file (every nodl.frontends extension is blocked or broken)'),
    'NODL020': ('error', 'a path given to a command cannot be read: missing, not permitted, a socket, '
                         'a dangling link, a directory that cannot be scanned or holds no NoDL files'),
    # -- NODL03x: writing files (nodl.writing) -----------------------
    'NODL030': ('error', 'a file cannot be written (no space, the file size limit, permissions); the previous file is left unchanged'),
    'NODL031': ('error', 'an output would replace a file nodl did not write (it has no nodl marker); --force replaces it'),
    'NODL032': ('error', 'an output would replace a file edited since nodl wrote it (its nodl marker no longer matches); --force replaces it'),
    'NODL033': ('error', 'an output path names one of the inputs (the same file, through links or hard links)'),
    'NODL034': ('error', 'an output path is a directory, not a file'),
    # -- NODL1xx: structure (the JSON Schemas) ------------------------------
    'NODL101': ('error', 'unknown key'),
    'NODL102': ('error', 'a required key is missing'),
    'NODL103': ('error', 'a value (or key) has the wrong type'),
    'NODL104': ('error', 'a value is not one of the allowed values'),
    'NODL105': ('error', 'a value is too small, too short, or a list has too few or too many items'),
    'NODL106': ('error', 'a string does not match the required pattern'),
    'NODL107': ('error', 'a value fits none (or more than one) of the allowed forms'),
    'NODL108': ('error', 'the document is not of the required kind (parameter, interface or node definition)'),
    # -- NODL2xx: semantic rules -------------------------------------------
    'NODL201': ('error', 'invalid ROS name (topic, service or action)'),
    'NODL202': ('error', 'invalid parameter name'),
    'NODL203': ('error', 'invalid interface type name (package/msg|srv|action/Type)'),
    'NODL204': ('error', 'the interface type is of the wrong kind for its section (a srv type on a topic)'),
    'NODL205': ('warning', 'a short interface type name (pkg/Type) without its namespace'),
    'NODL206': ('error', 'unknown parameter type'),
    'NODL207': ('error', 'invalid validator name'),
    'NODL208': ('warning', 'a validator name close to a built-in one will be called as a custom function'),
    'NODL209': ('error', 'the default value does not fit the parameter type'),
    'NODL210': ('error', 'the default value breaks a validator'),
    'NODL211': ('error', 'a validator does not apply to the parameter type'),
    'NODL212': ('error', 'validators conflict or are given twice'),
    'NODL213': ('error', 'invalid validator arguments'),
    'NODL214': ('warning', "a parameter of type 'none' has a default value, which is ignored"),
    'NODL215': ('error', 'an endpoint name appears twice in a section'),
    'NODL216': ('warning', 'a parameter or endpoint has no description'),
    'NODL217': ('error', 'invalid mixin reference'),
    'NODL218': ('warning', 'a mixin is listed twice'),
    'NODL219': ('error', 'a name or description holds a control character (C0/C1 but tab and newline)'),
    'NODL220': ('error', 'a name or description holds a bidirectional control (Trojan Source: '
                'U+202A-202E, U+2066-2069)'),
    'NODL221': ('error', 'launch or parameter file: a node name, namespace, remapping rule, parameter '
                'name or value holds a control character (C0/C1 but tab and newline)'),
    'NODL222': ('error', 'launch or parameter file: a node name, namespace, remapping rule, parameter '
                'name or value holds a bidirectional control (Trojan Source: U+202A-202E, U+2066-2069)'),
    'NODL223': ('error', 'policy: a name to be written (enclave, profile, grant) holds a control character '
                '(C1, DEL, CR): no policy is written'),
    'NODL224': ('error', 'policy: a name to be written (enclave, profile, grant) holds a bidirectional '
                'control (Trojan Source): no policy is written'),
    'NODL230': ('warning', 'QoS history KEEP_ALL with a depth: the middleware ignores the depth'),
    'NODL240': ('error', 'definitions folder: a file or folder in the wrong place (the layout is '
                'DIR/<package>/<executable>.nodl.yaml, DIR/<package>/interfaces/<name>.nodl.yaml, '
                'DIR/<package>/nodes.yaml)'),
    'NODL242': ('error', "definitions folder: nodes.yaml names a plugin class of another package than "
                "its folder's"),
    'NODL243': ('error', 'definitions folder: a package folder whose name is not a package name'),
    'NODL244': ('error', 'definitions folder: nodes.yaml is not a table {<executable>: {plugin, node_name}}'),
    'NODL245': ('warning', 'definitions folder: nodes.yaml records a node the folder has no definition of'),
    'NODL246': ('error', 'definitions folder: it, or a file in it, cannot be read (missing, not a folder)'),
    'NODL247': ('error', 'definitions folder: two files define the same node or interface'),
    'NODL250': ('error', 'types: the package of an interface type is not installed (not in the ament index)'),
    'NODL251': ('error', 'types: the package defines no such message, service or action type'),
    'NODL252': ('error', 'types: the type exists, but as another kind (a message used as a service type)'),
    'NODL253': ('warning', 'types: a short type name (pkg/Type) that resolves to an installed type'),
    'NODL254': ('error', 'types: the package is installed but defines no interface types'),
    'NODL255': ('error', "types: an interface package is not a dependency in the node's package.xml"),
    'NODL256': ('warning', "types: an interface package is only a build dependency in package.xml (not a run-time one)"),
    'NODL257': ('warning', 'types, at build time: an interface package is declared in package.xml but not installed'),
    'NODL258': ('error', 'types: an interface file (.msg, .srv, .action, .idl) cannot be read or parsed'),
    'NODL259': ('error', "types: the package's package.xml cannot be read, so dependencies are not checked"),
    'NODL270': ('warning', "doc: a type's field table is unavailable: its package is not installed"),
    'NODL271': ('warning', "doc: a type's field table is unavailable: the package defines no such type, or the name is not a full type name"),
    'NODL272': ('warning', "doc: a type's field table is unavailable: its interface file cannot be read or parsed"),
    'NODL273': ('error', 'doc: a target cannot be documented (no such file, package or node, or its definition does not resolve)'),
    'NODL274': ('warning', "doc: the system's graph cannot be drawn (the layout program is missing or fails)"),
    'NODL275': ('error', 'doc --check: a page on disk differs from what the definitions give (stale)'),
    'NODL276': ('error', 'doc --check: a page is missing, or cannot be read'),
    'NODL277': ('error', 'doc --check: a page nodl wrote is no longer made by the definitions (left over)'),
    # -- NODL3xx: composition ----------------------------------------------
    'NODL301': ('error', 'a mixin reference cannot be resolved'),
    'NODL302': ('error', 'a mixin is not a valid interface definition'),
    'NODL303': ('error', 'a mixin is a parameter or node definition, not an interface definition'),
    'NODL304': ('info', 'an entity overrides the one of an earlier layer'),
    'NODL305': ('error', 'this kind of document cannot be composed or shown as an interface'),
    'NODL306': ('error', 'nothing is registered under this name: no node definition for this package and '
                'executable, or no interface definition nodl://PACKAGE/NAME'),
    'NODL307': ('error', 'a layer changes the type of an entity of the base (the client library creates it)'),
    'NODL308': ('error', 'a layer changes the QoS of an entity of the base (the client library creates it)'),
    'NODL309': ('error', 'a layer changes read_only of a parameter of the base (the client library declares it)'),
    'NODL310': ('warning', 'a layer changes the type of an entity a mixin declares (the mixin\'s code and the node disagree)'),
    'NODL311': ('error', 'include dialect: an included document includes itself (a cycle), or a document is '
                'included twice'),
    # -- NODL4xx: live drift -----------------------------------------------
    'NODL401': ('error', 'drift: declared but not observed on the running node'),
    'NODL402': ('error', 'drift: observed on the running node but not declared'),
    'NODL403': ('error', 'drift: the observed interface type differs from the declared one'),
    'NODL404': ('error', 'drift: an observed QoS policy differs from the declared one'),
    'NODL405': ('error', 'drift: the observed parameter type differs from the declared one'),
    'NODL406': ('error', 'drift: the observed read_only flag differs from the declared one'),
    'NODL407': ('warning', "a parameter's current value breaks its declared validators"),
    'NODL408': ('info', 'cannot be verified: the middleware does not report it'),
    'NODL409': ('error', 'describe --launch: a node the launch file starts was not seen in the graph'),
    'NODL410': ('warning', 'describe --launch: instances of one executable disagree (left out of the merged definition)'),
    'NODL411': ('warning', 'describe --launch: instances differ by their parameters, which a definition cannot express (left out)'),
    'NODL412': ('warning', 'describe --launch: a final name no name the node could declare resolves to (written as observed)'),
    'NODL413': ('warning', 'describe --launch: a lifecycle node observed before configure lacks the endpoints it creates there'),
    'NODL414': ('warning', 'describe --launch: several nodes in the graph share a final name (observed together)'),
    'NODL415': ('warning', 'describe --launch: remapping rules only the running launch knows (names not undone)'),
    'NODL416': ('warning', 'describe --launch: a launched node that cannot be found or filed (final name or executable unknown)'),
    'NODL420': ('error', "version skew: a running endpoint's type hash differs from the installed definition's"),
    'NODL421': ('info', "version skew: an endpoint's type hash cannot be compared (not reported, or the installed file cannot be read)"),
    'NODL422': ('info', "version skew: a node's service types cannot be compared (no hash for services, no ~/get_type_description), said once per node"),
    'NODL423': ('warning', "describe: an observed endpoint's type differs from the installed definition (version skew), noted next to the entity"),
    'NODL430': ('error', 'monitor: an expected node is not running (not seen within the grace period, or gone from the graph)'),
    'NODL431': ('warning', 'monitor: a node is running that the expected system does not have'),
    'NODL432': ('warning', "monitor: a node is restarting (a new node of its name while the old one's participant lease runs)"),
    'NODL433': ('info', 'monitor: a node without a usable definition is monitored for presence only'),
    'NODL434': ('error', 'monitor: a node stopped answering its parameter services (killed or hung; before its lease ends)'),
    'NODL435': ('error', 'monitor: no message in the rate window on a topic whose definition declares a deadline'),
    'NODL436': ('warning', 'monitor: a topic with a declared deadline is published more slowly than 1/deadline (beyond the tolerance)'),
    'NODL437': ('error', 'monitor: the endpoints of a topic agree on its type name but not on its type hash (version skew)'),
    'NODL438': ('error', 'monitor: a parameter the definition declares read_only was changed at run time'),
    'NODL439': ('warning', 'monitor: shedding: the monitor cannot keep up within its CPU budget (graph scans spaced out)'),
    'NODL440': ('warning', 'monitor: a launched node cannot be monitored (its final name cannot be computed)'),
    'NODL441': ('warning', "monitor: shedding: a parameter event storm (more than 50 events a second from one node): every event is checked, the node's status refreshed and published at most every 20 ms"),
    'NODL442': ('warning', "monitor: parameter events never reached the monitor (a gap in the publisher's sequence numbers): the node's parameters are read again"),
    'NODL443': ('warning', 'monitor: the graph does not settle (it changed at least 10 times in 10 s): endpoint findings follow the last scan; the nodes whose endpoints keep changing are named'),
    # -- NODL5xx: system analysis (launch files: 501-539) -------------------
    'NODL501': ('error', 'launch file: an unknown tag (action) or a misplaced one'),
    'NODL502': ('error', 'launch file: an unknown attribute'),
    'NODL503': ('error', 'launch file: a required attribute is missing'),
    'NODL504': ('error', 'launch file: an attribute has an invalid value, or attributes conflict'),
    'NODL505': ('error', "launch argument: the value is not one of the argument's choices"),
    'NODL506': ('error', 'launch argument: a required argument (no default) is not given'),
    'NODL507': ('error', 'launch include cycle: a launch file includes itself'),
    'NODL508': ('error', 'launch limits: includes nest too deep, or too many entities'),
    'NODL509': ('error', 'launch file: an unknown substitution $(...)'),
    'NODL510': ('error', 'launch substitution failed: bad syntax, an unset variable, a failing $(eval)'),
    'NODL511': ('error', 'launch file: a package is not found in the ament index'),
    'NODL512': ('warning', 'launch file: a construct that only a running launch evaluates (OpaqueFunction, '
                'an unknown action); the nodes it starts are missing'),
    'NODL513': ('warning', 'launch file: a value known only at run time ($(command), $(log_dir))'),
    'NODL514': ('error', 'launch condition: the expression is neither true nor false'),
    'NODL515': ('error', 'launch include: the file is missing or unreadable'),
    'NODL516': ('error', 'Python launch file: it raised an exception, or has no generate_launch_description()'),
    'NODL517': ('error', 'parameter file: missing, unreadable or not NODE: {ros__parameters: ...}'),
    'NODL518': ('error', 'launch parameter: a value launch cannot type (a mapping, a mixed list, bad YAML)'),
    'NODL519': ('error', 'launch node: an invalid node name, namespace or remapping rule'),
    'NODL520': ('warning', 'launch argument: given but declared by no launch file'),
    'NODL521': ('error', 'launch substitution: a value (let, arg default, $(var), joined path) would pass the 16 MiB limit'),
    'NODL525': ('error', 'Python launch file: not run because --no-exec is set (its nodes are missing)'),
    'NODL526': ('warning', 'launch substitution: $(eval) not evaluated because --no-exec is set (its value is unknown)'),
    'NODL527': ('error', "launch file's Python code: it ended or crashed the sandbox process (os._exit, a signal)"),
    'NODL528': ('error', "launch file's Python code: it ran longer than --launch-timeout and was stopped"),
    'NODL529': ('error', "launch file's Python code: it needed more memory than --launch-memory"),
    'NODL530': ('warning', 'assumed-duplicate-node: two launched nodes share a final name the analysis assumed '
                '(launched without a name, none recorded); the programs may name themselves apart'),
    'NODL531': ('error', 'nodl analyse: the file given is not a launch file (a node definition, a parameter '
                'file, a package.xml, other text)'),
    'NODL532': ('error', 'nodl deps: a mixin of the node definition leads outside its package (an installed '
                'copy cannot reach it)'),
    'NODL533': ('error', "composable node: an extra argument rclcpp_components reads (use_intra_process_comms, "
                'forward_global_arguments) is not a bool: the container refuses to load the node'),
    # -- NODL55x-59x: system analysis (nodl analyse) ------------------------
    'NODL550': ('error', 'duplicate-node: two launched nodes end up with the same fully qualified name'),
    'NODL551': ('warning', 'multiple-publishers: more than one node publishes a topic (not on the allow list)'),
    'NODL552': ('error', 'type-mismatch: the endpoints of a topic, service or action disagree on its type'),
    'NODL553': ('error', 'qos-incompatible: the middleware would not connect a publisher and a subscription'),
    'NODL554': ('warning', 'qos-warning: the middleware would connect a publisher and a subscription with a warning'),
    'NODL555': ('warning', 'orphan-subscription: no node in the system publishes the topic'),
    'NODL556': ('warning', 'orphan-service-client: no node in the system serves the service'),
    'NODL557': ('warning', 'orphan-action-client: no node in the system serves the action'),
    'NODL558': ('info', 'orphan-publisher: no node in the system subscribes to the topic'),
    'NODL559': ('warning', "unused-remap: a node's remapping rule matches none of its entities"),
    'NODL560': ('warning', 'unknown-parameter: a parameter is set for a node whose definition does not declare it'),
    'NODL561': ('error', 'parameter-type: a parameter is set to a value of another type than declared'),
    'NODL562': ('error', "parameter-invalid: a parameter's value breaks its declared validators"),
    'NODL563': ('error', 'missing-parameter: a declared parameter without a default is set by nothing'),
    'NODL564': ('warning', 'no-definition: a launched node has no registered definition (its endpoints are unknown)'),
    'NODL565': ('warning', 'a node launched without a name takes the name of its executable (its registration records none)'),
    'NODL566': ('error', 'a launched node cannot be analysed: its definition does not compose, or its name, namespace or remapping is invalid'),
    'NODL567': ('warning', 'an analysis check plug-in is broken and was skipped'),
    'NODL568': ('warning', "draft-gaps: a node's definition is an extracted draft with entities still under # GAP "
                           '(what the analysis says about them cannot be judged)'),
    'NODL570': ('error', 'type-definition-mismatch: endpoints of a topic use one type name with different installed definitions'),
    # -- NODL6xx: SROS 2 policies (nodl policy) -----------------------------
    'NODL601': ('error', 'policy: a node has no definition, so its profile cannot be written (--allow-missing: a warning and an empty profile)'),
    'NODL602': ('error', 'policy: a final name cannot be granted in a policy (invalid, or DDS would read it as a pattern)'),
    'NODL603': ('warning', 'policy check: a name in the policy is a pattern (*, ?, [...]) and grants more than the node needs'),
    'NODL604': ('error', 'policy check: the policy lacks a grant the system needs (the node would fail at runtime)'),
    'NODL605': ('error', 'policy check: the policy grants a permission the system does not need (over-privilege)'),
    'NODL606': ('error', 'policy: the document breaks the structure SROS 2 requires (policy.xsd, version 0.2.0)'),
    'NODL607': ('error', 'policy check: the policy has no profile for a node of the system'),
    'NODL608': ('error', 'policy check: the policy has a profile for a node the system does not have'),
    'NODL609': ('error', 'policy check: a node\'s profile is in another enclave than the one the node runs in'),
    'NODL610': ('error', 'policy: enclave mapping problem (an invalid enclave path or entry, a node no entry or two enclaves match)'),
    'NODL611': ('error', 'policy: two nodes share one fully qualified name (DDS security cannot tell them apart)'),
    'NODL612': ('error', 'policy: the system has no nodes to write a policy for'),
    'NODL613': ('warning', 'policy: a node name in the enclave mapping is no node of the system (a misspelt name?)'),
    'NODL614': ('error', 'policy XInclude: more includes than the limit (an include bomb?); the rest are not expanded'),
    'NODL615': ('error', 'policy XInclude: the included text passes the total size limit; the rest is not expanded'),
    'NODL616': ('error', "policy XInclude: an href leads outside the including file's folder (after '..' and symbolic links)"),
    'NODL617': ('error', "policy: a node's definition is an extracted draft with entities still under # GAP: "
                         'nothing is granted for them (--allow-gaps: a warning)'),
    # -- NODL70x: parameter files checked against definitions (nodl params check) --
    'NODL701': ('error', "parameter file: a parameter the node's definition does not declare (a warning "
                'under a wildcard key, which also serves other nodes)'),
    'NODL702': ('error', 'parameter file: a value of another type than declared (as strict as a node: '
                'an integer for a double parameter is an error)'),
    'NODL703': ('error', "parameter file: a value breaks the parameter's validators, or an empty list leaves a typed parameter unset"),
    'NODL704': ('error', 'parameter file: a required parameter (no default) is set by none of the files'),
    'NODL705': ('warning', 'parameter file: no node key of the files applies to the node'),
    'NODL706': ('error', 'parameter file check: the launch file cannot be read, or starts no node with a definition'),
    'NODL707': ('error', 'code generation: an option is not a valid name (--node-name, --class-name, --namespace, a package name, a keyword)'),
    'NODL708': ('error', 'a file would be written outside the output folder (a generated path that leaves it, or a folder under it that is a symbolic link to a place outside)'),
    'NODL710': ('error', "parameter file read by rcl: a YAML alias (rcl refuses aliasing: the node fails to start)"),
    'NODL711': ('warning', 'parameter file read by rcl: a YAML anchor (rcl ignores it; no alias may use it)'),
    'NODL712': ('error', "parameter file read by rcl: a merge key '<<' (rcl has none: it reads '<<' as a parameter name)"),
    # -- NODL8xx: dialects and conversion ----------------------------------
    'NODL801': ('error', 'legacy XML: an element, attribute or text the legacy format does not have'),
    'NODL802': ('error', 'legacy XML: a required attribute is missing or empty'),
    'NODL803': ('error', 'legacy XML: an attribute has an invalid value'),
    'NODL804': ('error', 'legacy XML: unsupported legacy NoDL version'),
    'NODL805': ('warning', "legacy XML: <interface> has no 'version' attribute"),
    'NODL806': ('error', 'legacy XML: the root element is missing or not the expected one'),
    'NODL807': ('error', 'legacy XML: something is declared twice'),
    'NODL808': ('error', 'legacy XML: an endpoint has no role, or conflicting roles'),
    'NODL809': ('warning', 'legacy XML: the file declares no nodes'),
    'NODL810': ('error', 'package.xml: the interface export is missing or invalid'),
    'NODL811': ('warning', 'conversion: a legacy setting has no NoDL v2 meaning and is dropped'),
    'NODL812': ('warning', 'conversion: a value NoDL v2 requires is written as a default or completed; check it'),
    'NODL813': ('error', 'conversion: a legacy value cannot be expressed in NoDL v2'),
    'NODL814': ('error', 'conversion: a node cannot get a file of its own (a name unusable as a file name, '
                'or two nodes for one file)'),
    'NODL815': ('warning', 'legacy XML: something is given twice, redundantly (a role, an exported path)'),
    'NODL816': ('warning', 'conversion: an executable holds several nodes; each gets a file named after both'),
    'NODL817': ('error', 'legacy XML (or other XML) given where a NoDL v2 document is read; nodl convert '
                'converts legacy files'),
    'NODL818': ('error', "include dialect: a 'ref' is not a URI (scheme://body, such as nodl://PACKAGE/NAME "
                'or local://FILE); a bare path or a malformed URI (nodl:/x, ://x) names no resolver'),
    'NODL851': ('warning', "include dialect: the reference implementation's include/includes file is read "
                'as a node definition (base + mixins + main); nodl convert rewrites it'),
    'NODL852': ('error', 'include dialect: an include entry is not a mapping with one ref'),
    'NODL853': ('error', "include dialect: both 'include' and 'includes' are given"),
    'NODL854': ('warning', 'include dialect conversion: the converted file is written outside the source '
                'package, so a local include cannot be reached from it'),
    'NODL861': ('error', 'a generate_parameter_library file, not a NoDL document (nodl convert --from genparamlib)'),
    'NODL862': ('warning', 'generate_parameter_library: parameters under __map_ segments have no NoDL form '
                'and are not converted'),
    'NODL863': ('error', 'generate_parameter_library: not a namespace of parameters (two top-level keys, '
                'a value that is neither a parameter nor a namespace)'),
    'NODL864': ('warning', 'generate_parameter_library export: a parameter has no generate_parameter_library '
                "form (type 'none', a name that is not a C++ identifier path) and is left out"),
    # -- NODL9xx: extraction from source (901-929: the frame and Python) ---
    'NODL901': ('warning', 'extraction gap: a topic, service or action name is computed at run time (the entity is left commented out)'),
    'NODL902': ('warning', 'extraction gap: an interface type is not a constant the extractor can resolve'),
    'NODL903': ('warning', 'extraction gap: a QoS profile is computed at run time, or none is given'),
    'NODL904': ('warning', 'extraction gap: a parameter name is computed at run time'),
    'NODL905': ('warning', "extraction gap: a parameter's type, default value or descriptor is computed at run time"),
    'NODL906': ('error', 'a source file cannot be parsed (a syntax error, nesting too deep); nothing is extracted from it'),
    'NODL907': ('error', 'a source file cannot be read: not permitted, not UTF-8, or larger than the 10 MB limit'),
    'NODL908': ('warning', 'generated code is not read (extract from what generates it)'),
    'NODL909': ('warning', "extraction gap: an entity whose name depends on a plug-in (image_transport's transports)"),
    'NODL910': ('warning', 'extraction gap: an entity made through a call whose arguments are not written out (*args, **kwargs)'),
    'NODL911': ('info', 'a node no entry point runs (its draft is named after it), or a build file that cannot be read'),
    'NODL912': ('error', 'no node found in the paths given to nodl extract'),
    'NODL913': ('error', 'nodl extract -o FILE or --diff: not exactly one node found (give -o DIR, or one node\'s sources)'),
    'NODL914': ('warning', 'an extracted entity is not valid NoDL (an invalid name, a default of the wrong type); left commented out'),
    'NODL915': ('warning', 'a generate_parameter_library file a node reads cannot be found or read: its parameters are a gap'),
    'NODL920': ('error', 'extract --diff: created by the source but not in the definition'),
    'NODL921': ('error', 'extract --diff: in the definition but not created by the source'),
    'NODL922': ('error', 'extract --diff: the source and the definition give different types'),
    'NODL923': ('error', 'extract --diff: the source and the definition give different QoS'),
    'NODL924': ('error', "extract --diff: a parameter's default value, read_only or bounds differ"),
    'NODL925': ('error', 'extract --diff: the source and the definition give different bases (node, lifecycle_node)'),
    'NODL926': ('info', 'extract --diff: not compared, the source leaves it open (a gap)'),
    # -- NODL930-959: extraction from C++ (rclcpp) sources and CMakeLists.txt ---
    'NODL930': ('error', "C++ extraction needs the tree-sitter C++ parser (pip install 'nodl-toolkit[extract]')"),
    'NODL931': ('error', 'a C++ source or CMakeLists.txt cannot be read (not permitted, binary data, no such file)'),
    'NODL932': ('warning', 'a C++ source larger than the 2 MiB limit is not read'),
    'NODL933': ('info', 'generated C++ code is not read (extract from what generates it)'),
    'NODL934': ('warning', 'the C++ parser cannot read part of a source (a macro it cannot expand, a syntax error); what it creates may be missing'),
    'NODL935': ('warning', 'a C++ macro creates entities; what it creates where it is used is not extracted'),
    'NODL936': ('warning', 'C++ extraction gap: an interface type is a template parameter (a class template node)'),
    'NODL937': ('warning', 'C++ extraction gap: a topic, service, action or parameter name is computed at run time'),
    'NODL938': ('warning', 'C++ extraction gap: an interface or parameter type is not one the extractor can resolve (a type adapter, no default)'),
    'NODL939': ('warning', 'C++ extraction gap: a QoS profile is computed at run time, or none is given'),
    'NODL940': ('warning', "C++ extraction gap: a parameter's default value or descriptor is computed at run time"),
    'NODL941': ('warning', "C++ extraction gap: a name is the value of a declared parameter (set when the node starts)"),
    'NODL942': ('warning', "C++ extraction gap: image_transport's topics depend on the transport plug-ins installed"),
    'NODL943': ('info', "a C++ node's name is computed at run time"),
    'NODL944': ('info', 'a C++ node class no executable builds (a component only), or an entity call not tied to a node'),
    'NODL945': ('warning', 'CMakeLists.txt cannot be read from a command on (unbalanced parentheses, an unterminated string)'),
    'NODL946': ('warning', 'CMakeLists.txt: a target, source or component depends on what the reader cannot know (a variable, a while loop)'),
    # -- NODL960-969: nodl extract across languages and modules, and the overlay it writes ---
    'NODL960': ('warning', "extraction gap: a node's interface comes from a base class or a definition read at run time that is not extracted (the toolkit's NodlNode, a class generated by nodl generate)"),
    'NODL961': ('info', "nodl extract -o DIR: a component's plugin class is not in its package's namespace, so nodes.yaml cannot record it"),
    # -- NODL970-989: nodl system, the composer of launch files ---
    'NODL970': ('error', 'nodl system: no node of the composition is called so (or the name fits several)'),
    'NODL971': ('error', 'nodl system: the node has no such endpoint or parameter (or no definition to know it by)'),
    'NODL972': ('error', 'nodl system connect: these endpoints cannot be joined (two publishers, a publisher and a service...)'),
    'NODL973': ('error', 'nodl system connect: the two endpoints have different interface types'),
    'NODL974': ('error', 'nodl system connect: the QoS profiles cannot connect (the middleware would not match them)'),
    'NODL975': ('warning', 'nodl system connect: whether the QoS profiles match depends on what the middleware picks'),
    'NODL976': ('error', 'nodl system: the remapping rule cannot be written (the rules that decide the name are read-only, or another rule wins)'),
    'NODL977': ('error', 'nodl system set: the value is not of the parameter\'s type, or breaks one of its validators'),
    'NODL978': ('error', 'nodl system set: the node declares no such parameter'),
    'NODL979': ('info', 'nodl system: part of the launch file is kept verbatim and shown read-only (a condition, an include, Python code, substitutions)'),
    'NODL980': ('error', 'nodl system: the launch file changed on disk since it was read; not saved'),
    'NODL981': ('error', 'nodl system new: the file exists already (give --force to replace it)'),
    'NODL982': ('error', 'nodl system add/rename: the name or namespace is invalid, or a node of that name is in the composition already'),
    'NODL983': ('error', 'nodl system: the node (or the file) is read-only: its entry is not declarative'),
    'NODL984': ('error', 'nodl system: the file cannot be read as a launch file (syntax, root, file name ending)'),
    'NODL985': ('warning', 'nodl system: no definition is found for the node; its endpoints and parameters are not known or checked'),
    'NODL986': ('info', 'nodl system connect/disconnect: nothing to do (already connected, or not connected)'),
    'NODL987': ('error', 'nodl system disconnect: the names meet without a rule of the node\'s own entry; rename one side instead'),
    'NODL988': ('error', 'nodl system remap: a remapping rule that rcl would refuse (not FROM:=TO, or a name that is not valid)'),
    'NODL989': ('warning', "nodl system remap: a rule never applies (an earlier rule of the node's entry has the same FROM)"),
    # -- NODL990-999: nodl studio, the composer's local web application ---
    'NODL990': ('error', 'nodl studio: the file is outside the folders the studio was started with (the launch file\'s folder, --definitions)'),
    'NODL991': ('error', 'nodl studio: its browser libraries or its web server are not installed'),
    'NODL992': ('error', 'nodl studio: the port cannot be listened on (taken, or not permitted)'),
    'NODL994': ('error', "nodl studio: the launch files' Python code is not run (the studio was started with --no-exec)"),
}


def explain(code: str) -> str:
    """The one-line explanation of ``code`` (KeyError for an unknown code)."""
    return CODES[code][1]


def default_severity(code: str) -> str:
    """``error``, ``warning`` or ``info``: how bad ``code`` is unless promoted (KeyError if unknown)."""
    return CODES[code][0]


def is_code(text: str) -> bool:
    """True if ``text`` is a catalogued code."""
    return text in CODES


def close_codes(text: str) -> list[str]:
    """Catalogued codes that look like ``text`` (for a "did you mean" hint)."""
    wanted = text.upper()
    # the codes a prefix names come first ('nodl21': NODL210...), then those spelled alike
    return close_matches(wanted, CODES, most=3, prefix=len(wanted) > 4)


def catalogue_markdown() -> str:
    """The user documentation of every code (``docs/diagnostics.md`` is this text)."""
    out = [
        '# Diagnostic codes',
        '',
        '<!-- Generated from nodl/codes.py; tests/test_codes.py keeps them equal. -->',
        '',
        'Every problem the toolkit reports carries a stable code, printed at the end of the',
        'line (`file:4:7: error: ... [base] [NODL104]`) and in the `code` field of the JSON and',
        'SARIF output. A code keeps its meaning from release to release.',
        '',
        'Silence a code with `--ignore CODE` or make it fail with `--error CODE` (both',
        'repeatable, also comma-separated), or for a whole tree in a `nodl.toml`, or a',
        '`[tool.nodl]` table of `pyproject.toml`, found upward from the checked file:',
        '',
        '```toml',
        '[tool.nodl]            # in nodl.toml, the same keys at the top level',
        'ignore = ["NODL216"]   # no warning for missing descriptions',
        'error = ["NODL205"]    # short type names fail',
        '```',
        '',
        'Options on the command line win over the files. A file can also silence warnings for',
        'itself with a first-line comment `# nodl: ignore=NODL216` (what `nodl describe` and',
        '`nodl convert` write, as they cannot know descriptions); the comment never silences',
        'an error.',
        '',
        'The severity shown is the default one.',
    ]
    current = None
    for code, (severity, explanation) in CODES.items():
        stage = code[4]
        if stage != current:
            current = stage
            out += ['', f'## NODL{stage}xx: {RANGES[stage]}', '', '| code | severity | meaning |',
                    '| --- | --- | --- |']
        escaped = explanation.replace('|', '\\|')
        out.append(f'| {code} | {severity} | {escaped} |')
    return '\n'.join(out) + '\n'
