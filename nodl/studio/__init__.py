"""``nodl studio``: the composer's local web application.

A Starlette application (:mod:`nodl.studio.app`) served by uvicorn on loopback only,
every request carrying a random token (:mod:`nodl.studio.guard`), reading and writing
only under the folders it was started with.  Its JSON API edits a
:class:`nodl.composer.Composition` (:mod:`nodl.studio.session`): the studio has no model
of its own, and saving writes the launch file through the composer, as ``nodl system``.
The page (``static/``) draws the system with Cytoscape.js (:mod:`nodl.studio.vendor`).
"""
