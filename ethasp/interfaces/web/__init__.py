"""The dialogue as a local web page (``ethasp serve``): the HTTP API
(:mod:`~ethasp.interfaces.web.app`), the server (:mod:`~ethasp.interfaces.web.server`),
dialogues and jobs (:mod:`~ethasp.interfaces.web.workspace`,
:mod:`~ethasp.interfaces.web.jobs`) and the page itself (``static/``)."""
