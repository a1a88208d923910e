"""The command line: ``nodl <verb>`` and ``ros2 nodl <verb>``.

Verbs are entry points in the ``nodl.verbs`` group; each verb module only
parses arguments and calls the library.
"""
