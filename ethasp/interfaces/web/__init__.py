"""The dialogue as a local web page (``ethasp serve``): the HTTP API
(:mod:`~ethasp.interfaces.web.app`), the server (:mod:`~ethasp.interfaces.web.server`),
dialogues and jobs (:mod:`~ethasp.interfaces.web.workspace`,
:mod:`~ethasp.interfaces.web.jobs`), the worker processes that make the
dialogues' moves (:mod:`~ethasp.interfaces.web.workers`,
:mod:`~ethasp.interfaces.web.moves`) and the page itself (``static/``)."""
