"""The page's HTTP API (Flask): the model at a glance, dialogues and their
moves, jobs, saved dialogues and pictures.

Only the model given to :func:`create_app` is served; no request carries
model text or file paths.  Requests that change something are JSON
(``Content-Type: application/json``, which a page of another site cannot send
without the server's consent) and, when a browser names their origin, come
from the page itself.  Bound to loopback, the server also answers only to
loopback host names (a guard against DNS rebinding).  Errors are JSON
``{"error": "one line"}``, with the messages of the command line.
"""

from __future__ import annotations

from urllib.parse import urlsplit

from flask import Flask, Response, jsonify, request
from werkzeug.exceptions import HTTPException

from ethasp.errors import InputError
from ethasp.interfaces.web.moves import Shown
from ethasp.interfaces.web.views import explain_json, model_json, state_json
from ethasp.interfaces.web.workspace import Refused, Workspace

LOOPBACK_NAMES = {"127.0.0.1", "localhost", "::1"}
MAX_BODY = 2_000_000  # bytes of one request
WAIT = 0.3  # seconds a move waits for its job before answering "running"

SECURITY_HEADERS = {
    "Content-Security-Policy": "default-src 'self'; img-src 'self' data: blob:; "
    "object-src 'none'; base-uri 'none'; frame-ancestors 'none'; "
    "form-action 'self'",
    "X-Content-Type-Options": "nosniff",
    "Referrer-Policy": "no-referrer",
    "X-Frame-Options": "DENY",
}


def _hostname(netloc: str) -> str:
    return (urlsplit(f"//{netloc}").hostname or "").lower()


def create_app(workspace: Workspace, loopback: bool = True) -> Flask:
    """The web application over a workspace (the served model and its dialogues).

    ``loopback``: the server is bound to a loopback address, so requests must
    name a loopback host.
    """
    app = Flask(__name__, static_folder="static", static_url_path="/static")
    app.config["MAX_CONTENT_LENGTH"] = MAX_BODY
    app.json.sort_keys = False
    app.extensions["ethasp"] = workspace

    # -- guards -------------------------------------------------------------------------

    @app.before_request
    def guard():
        if loopback and _hostname(request.host) not in LOOPBACK_NAMES:
            return _error(
                403, f"forbidden host {request.host!r}: the page is served on loopback only"
            )
        if request.method == "POST":
            origin = request.headers.get("Origin")
            if origin is not None and urlsplit(origin).netloc.lower() != request.host.lower():
                return _error(403, f"forbidden origin {origin!r}")
            if not request.is_json:
                return _error(415, "requests must be JSON (Content-Type: application/json)")
        return None

    @app.after_request
    def headers(response: Response) -> Response:
        for name, value in SECURITY_HEADERS.items():
            response.headers.setdefault(name, value)
        if request.path.startswith("/api/"):
            response.headers["Cache-Control"] = "no-store"
        return response

    @app.errorhandler(InputError)
    def input_error(error: InputError):
        return _error(400, str(error))

    @app.errorhandler(Refused)
    def refused(error: Refused):
        return _error(error.status, str(error))

    @app.errorhandler(HTTPException)
    def http_error(error: HTTPException):
        if error.code == 413:
            return _error(413, f"request too large (at most {MAX_BODY} bytes)")
        return _error(error.code or 500, error.description or error.name)

    # -- the page ---------------------------------------------------------------------------

    @app.get("/")
    def page():
        return app.send_static_file("index.html")

    @app.get("/api/model")
    def model():
        return jsonify(model_json(workspace))

    # -- dialogues --------------------------------------------------------------------------

    def body() -> dict:
        data = request.get_json(silent=True)
        if not isinstance(data, dict):
            raise InputError("the request must be a JSON object")
        return data

    def moved(session, job):
        job.thread.join(WAIT)
        return jsonify({"session": session.id, "job": job.to_json()}), 202

    @app.post("/api/sessions")
    def new_session():
        data = body()
        session = workspace.new_session()
        if data.get("dialogue") is not None:
            job = workspace.load(session, data["dialogue"], data.get("name") or "dialogue.json")
        else:
            job = workspace.start(session, data.get("principle"), data.get("plan") or "")
        return moved(session, job)

    @app.get("/api/sessions/<key>")
    def state(key: str):
        return jsonify(state_json(workspace, workspace.session(key)))

    @app.get("/api/sessions/<key>/explain")
    def explain(key: str):
        session = workspace.session(key)
        step = request.args.get("step")
        if step is not None:
            if not step.isdigit() or len(step) > 7:
                raise InputError(f"why step {step}: expected a step number")
            step = int(step)
        return jsonify(explain_json(workspace, session, step))

    @app.get("/api/sessions/<key>/job")
    def job(key: str):
        session = workspace.session(key)
        return jsonify(
            {"session": session.id, "job": session.job.to_json() if session.job else None}
        )

    @app.post("/api/sessions/<key>/start")
    def start(key: str):
        session, data = workspace.session(key), body()
        return moved(
            session, workspace.start(session, data.get("principle"), data.get("plan") or "")
        )

    @app.post("/api/sessions/<key>/ask")
    def ask(key: str):
        session, data = workspace.session(key), body()
        return moved(session, workspace.ask(session, data.get("question", "")))

    @app.post("/api/sessions/<key>/undo")
    def undo(key: str):
        session = workspace.session(key)
        body()
        return moved(session, workspace.undo(session))

    @app.post("/api/sessions/<key>/load")
    def load(key: str):
        session, data = workspace.session(key), body()
        return moved(
            session,
            workspace.load(session, data.get("dialogue", ""), data.get("name") or "dialogue.json"),
        )

    @app.post("/api/sessions/<key>/principle")
    def principle(key: str):
        session, data = workspace.session(key), body()
        workspace.switch(session, data.get("principle", ""))
        return jsonify(state_json(workspace, session))

    @app.post("/api/sessions/<key>/cancel")
    def cancel(key: str):
        session = workspace.session(key)
        body()
        job = workspace.cancel(session)
        return jsonify({"session": session.id, "job": job.to_json() if job else None})

    # -- files ----------------------------------------------------------------------------------

    @app.get("/api/sessions/<key>/dialogue.json")
    def save(key: str):
        dialogue = workspace.session(key).require()
        response = jsonify(dialogue.to_json())
        response.headers["Content-Disposition"] = 'attachment; filename="ethasp-dialogue.json"'
        return response

    # The pictures are drawn from what the session keeps (no clingo here).

    def shown(key: str) -> Shown:
        session = workspace.session(key)
        session.require()
        return session.shown

    @app.get("/api/sessions/<key>/current.svg")
    def current_picture(key: str):
        kept = shown(key)
        report = kept.report
        return _svg(
            workspace.pictures_of(kept).report(
                report,
                f"current plan: {workspace.model.naming.actions(report.plan) or '(empty)'}",
                words=_words(),
            )
        )

    @app.get("/api/sessions/<key>/better/<principle>.svg")
    def better_picture(key: str, principle: str):
        kept = shown(key)
        report = kept.report
        judgement = next((j for j in report.judgements if j.principle == principle), None)
        if judgement is None or judgement.better_plan is None:
            raise Refused(404, f"no better plan under {principle} for the current plan")
        return _svg(workspace.pictures_of(kept).better(report, judgement, words=_words()))

    @app.get("/api/sessions/<key>/explain.svg")
    def explain_picture(key: str):
        kept = shown(key)
        return _svg(workspace.pictures_of(kept).explained(kept.explained, words=_words()))

    @app.get("/api/sessions/<key>/steps/<int:number>.svg")
    def step_picture(key: str, number: int):
        kept = shown(key)
        steps = kept.dialogue.steps
        if not 1 <= number <= len(steps):
            raise Refused(404, f"no question {number} in this dialogue")
        return _svg(workspace.pictures_of(kept).answer(steps[number - 1].answer, words=_words()))

    @app.get("/api/sessions/<key>/steps/<int:number>/repair.svg")
    def repair_picture(key: str, number: int):
        kept = shown(key)
        steps = kept.dialogue.steps
        if not 1 <= number <= len(steps):
            raise Refused(404, f"no question {number} in this dialogue")
        repaired = kept.repairs.get(number)
        picture = (
            workspace.pictures_of(kept).repair(steps[number - 1].answer, _words(), repaired)
            if repaired is not None
            else None
        )
        if picture is None:
            raise Refused(404, f"the answer to question {number} has no repaired plan")
        return _svg(picture)

    return app


def _words() -> bool:
    """Pictures carry their explanations in words unless ``?words=0`` (the page
    shows the words beside them)."""
    return request.args.get("words", "1") != "0"


def _svg(text: str) -> Response:
    return Response(text, mimetype="image/svg+xml")


def _error(status: int, message: str):
    return jsonify({"error": message}), status
