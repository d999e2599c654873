// The ethasp page: the dialogue of contrastive questions about a plan.
// It talks to the server's JSON API (ethasp/interfaces/web/app.py); the
// server keeps the dialogue, the page keeps the session id and a copy of the
// dialogue in localStorage, so a reload (or a restarted server) finds it again.
"use strict";

const $ = (id) => document.getElementById(id);
const POLL_MS = 250;

let model = null;     // GET /api/model
let sid = null;       // the session id
let state = null;     // GET /api/sessions/<sid>
let viewing = null;   // the number of the answer shown
let selected = null;  // the action chosen by a click: {term, shown}
let running = false;  // a job is running
let explainedPlan = null;  // the plan whose step-by-step explanation may be shown

// -- HTTP ------------------------------------------------------------------------------

class ApiError extends Error {
  constructor(status, message) { super(message); this.status = status; }
}

async function call(method, path, data) {
  const options = { method, headers: { "Accept": "application/json" } };
  if (method === "POST") {
    options.headers["Content-Type"] = "application/json";
    options.body = JSON.stringify(data || {});
  }
  let response;
  try {
    response = await fetch(path, options);
  } catch (error) {
    throw new ApiError(0, "the server cannot be reached (was it stopped?)");
  }
  let body = null;
  try { body = await response.json(); } catch (error) { body = null; }
  if (!response.ok) {
    throw new ApiError(response.status, (body && body.error) || `HTTP ${response.status}`);
  }
  return body;
}
const get = (path) => call("GET", path);
const post = (path, data) => call("POST", path, data);

// -- small DOM helpers ------------------------------------------------------------------------

function el(tag, attributes, ...children) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes || {})) {
    if (value === null || value === undefined || value === false) continue;
    if (name === "class") node.className = value;
    else if (name === "text") node.textContent = value;
    else if (name.startsWith("on")) node.addEventListener(name.slice(2), value);
    else node.setAttribute(name, value === true ? "" : value);
  }
  for (const child of children.flat()) {
    if (child === null || child === undefined || child === false) continue;
    node.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return node;
}

function clear(node) { while (node.firstChild) node.removeChild(node.firstChild); return node; }

function utilityText(utility) {
  return utility > 0 ? `+${utility}` : utility < 0 ? `\u2212${-utility}` : "0";
}

// Errors and notes are shown where the user acted (the slot of that panel:
// the Ask panel, the History panel, ...) and scrolled into view there.
let messagesAt = null;   // the slot of the last move, null: the top of the page

function place(slot) {
  messagesAt = slot || null;
  const target = slot || $("messages-home");
  if ($("messages").parentNode !== target) target.append($("messages"));
}

let revealedAt = 0;    // when a message was last scrolled into view
const SETTLING_MS = 3000;

function reveal(box) {
  // After the layout has settled (a render may have just changed it).
  revealedAt = Date.now();
  requestAnimationFrame(() => { if (!box.hidden) box.scrollIntoView({ block: "nearest" }); });
}

function settled() {
  // A picture arrived and may have moved the page: an error shown just before
  // stays in view (a note does not pull the page back from the answer).
  if (Date.now() - revealedAt <= SETTLING_MS && !$("error").hidden) reveal($("error"));
}

function showError(message) {
  const box = $("error");
  if (!message) { box.hidden = true; box.textContent = ""; return; }
  box.textContent = `error: ${message}`;
  box.hidden = false;
  reveal(box);
}

function showNote(message) {
  const box = $("note");
  box.hidden = !message;
  box.textContent = message || "";
  if (message) reveal(box);
}

// -- keeping the session across reloads -------------------------------------------------------------

function storeKey() { return `ethasp:${model.key}`; }

function remember() {
  try {
    localStorage.setItem(storeKey(), JSON.stringify({
      session: sid, dialogue: state && state.dialogue ? state.dialogue : null }));
  } catch (error) { /* storage full or disabled: the server still keeps the dialogue */ }
}

function remembered() {
  try { return JSON.parse(localStorage.getItem(storeKey()) || "null"); }
  catch (error) { return null; }
}

// -- jobs: long requests, with progress and cancel ----------------------------------------------------

function setBusy(job) {
  running = Boolean(job && job.state === "running");
  $("status").hidden = !running;
  for (const button of document.querySelectorAll("#ask-form button, #undo, #start, #action-menu button, #drop-question, #drop-offer button, #shorter, #cheaper, #explain-plan")) {
    button.disabled = running;
  }
  $("under").disabled = running || !state || !state.dialogue;
  if (!running) return;
  $("status-text").textContent = `${job.description}\u2026`;
  $("status-time").textContent = `${job.elapsed.toFixed(1)} s`;
  $("status-progress").textContent = job.progress || "";
}

async function follow(reply) {
  // A move answered {session, job}: poll the job until it ends, then show the state.
  sid = reply.session;
  let job = reply.job;
  setBusy(job);
  while (job && job.state === "running") {
    await new Promise((resolve) => setTimeout(resolve, POLL_MS));
    job = (await get(`/api/sessions/${sid}/job`)).job;
    setBusy(job);
  }
  setBusy(null);
  await refresh();
  if (job && job.error) showError(job.error);  // failed, or ended at a limit
  if (job && job.note) showNote(job.note);
  return job;
}

async function move(request, slot) {
  const offer = $("drop-offer");
  if (offer) offer.remove();  // an offer to drop a question is answered by any move
  place(slot);
  showError(null);
  showNote(null);
  try {
    const job = await follow(await request());
    return job;
  } catch (error) {
    setBusy(null);
    showError(error.message);
    return null;
  }
}

async function refresh() {
  state = await get(`/api/sessions/${sid}`);
  remember();
  render();
}

// -- rendering -------------------------------------------------------------------------------------------

function renderModel() {
  $("model-name").textContent = model.name;
  $("version").textContent = `ethasp ${model.version}`;
  document.title = `ethasp \u2013 ${model.name}`;
  const glance = model.model;
  const box = clear($("model"));
  if (glance.agent) box.append(el("p", {}, "Agent: ", el("strong", { text: glance.agent.name })));

  const actions = el("table", { class: "glance", id: "model-actions" },
    el("tr", {}, el("th", { text: "action" }), el("th", { text: "label" }), el("th", { text: "utility" })));
  for (const action of glance.actions) {
    actions.append(el("tr", {},
      el("td", {}, el("button", {
        class: `chip ${action.moral}`, type: "button", "data-term": action.term,
        title: `${action.moral}: ask about ${action.shown}`,
        onclick: () => choose(action.term, action.shown) }, action.shown)),
      el("td", { class: "label", text: action.label }),
      el("td", { class: action.moral, text: utilityText(action.utility) })));
  }
  box.append(collapsible(`Actions (${glance.actions.length})`, actions, glance.actions.length));

  const variables = el("table", { class: "glance", id: "model-variables" },
    el("tr", {}, el("th", { text: "variable" }), el("th", { text: "true" }), el("th", { text: "false" })));
  const goal = new Set(glance.goal.map((fact) => fact.literal));
  for (const variable of glance.variables) {
    const cell = (fact, isTrue) => el("td", { class: fact.moral, title: `${fact.shown}: ${fact.moral}, utility ${fact.utility}` },
      el("div", {}, fact.utility ? el("strong", { text: utilityText(fact.utility) }) : null,
        (variable.initial === isTrue) ? el("span", { class: "muted", text: " initially" }) : null,
        goal.has(fact.literal) ? el("span", { class: "muted", text: " goal" }) : null),
      fact.label ? el("div", { class: "label", text: fact.label }) : null);
    variables.append(el("tr", {}, el("td", {}, el("button", {
        class: "chip", type: "button", "data-variable": variable.term,
        title: `ask about ${variable.shown}`, onclick: () => chooseFact(variable) }, variable.shown)),
      cell(variable.true, true), cell(variable.false, false)));
  }
  box.append(collapsible(`Variables (${glance.variables.length})`, variables,
    glance.variables.length));
  box.append(el("p", { class: "muted" },
    "Goal: ", glance.goal.map((fact) => fact.shown).join(", ") || "none"));

  // Contrast plans and first plans are searched under a principle: the menus
  // offer the principles that can restrict plan search (all judge plans).
  for (const select of [$("under"), $("start-principle")]) {
    clear(select);
    for (const name of model.restricting) select.append(el("option", { value: name, text: name }));
  }
  $("start-principle").value = model.principle;
  $("under").value = model.principle;  // until the dialogue says otherwise
  $("under").disabled = !state || !state.dialogue;
  $("question").maxLength = model.limits.question;
  $("start-plan").maxLength = model.limits.plan;
  if (model.choices) renderChoices(box);
}

function renderChoices(box) {
  // A causal agency model: its plans are its actions, one chosen at a time.
  // The first plan is chosen from a list; there are no timelines to draw and
  // no steps to explain.
  const list = el("datalist", { id: "choices" });
  for (const choice of model.choices) list.append(el("option", { value: choice.term, text: choice.shown }));
  box.append(list);
  $("start-plan").setAttribute("list", "choices");
  $("start-plan").placeholder = "the action chosen (empty: the first permissible under the principle)";
  $("current-heading").textContent = "Current choice";
  const table = el("table", { class: "glance", id: "model-choices" },
    el("tr", {}, el("th", { text: "action" })));
  for (const choice of model.choices) {
    table.append(el("tr", {}, el("td", {}, el("button", {
      class: "chip", type: "button", "data-term": choice.term, title: `ask about ${choice.shown}`,
      onclick: () => choose(choice.term, choice.shown) }, choice.shown))));
  }
  box.prepend(collapsible(`Choices (${model.choices.length})`, table, model.choices.length));
  for (const id of ["explain-plan", "shorter", "current-picture", "answer-picture"]) $(id).hidden = true;
  for (const button of document.querySelectorAll(".zoom")) button.parentElement.hidden = true;
}

function verdictNode(side) {
  const word = side.permissible ? "permissible" : "impermissible";
  return el("span", {}, el("span", { class: `verdict ${word}`, text: word }),
    el("span", { class: "status", text: side.status === "proven" ? "proven" : "bounded: as far as searched" }));
}

// A long section (the model's tables) is folded when it has more rows than this.
const OPEN_ROWS = 12;
// A literal longer than this shows its start; a reason with more literals, its first ones.
const LONG_LITERAL = 160;
const MANY_LITERALS = 12;
// Characters of a history entry after its question.
const HISTORY_WORDS = 90;

function collapsible(title, content, rows) {
  return el("details", { class: "glance", open: rows <= OPEN_ROWS }, el("summary", { text: title }),
    content);
}

function expander(shown, label) {
  // A button that shows the whole of something shortened, and shortens it again.
  const button = el("button", { type: "button", class: "more", "aria-expanded": "false" }, label);
  button.addEventListener("click", () => {
    const open = button.getAttribute("aria-expanded") !== "true";
    button.setAttribute("aria-expanded", String(open));
    button.textContent = open ? "show less" : label;
    shown(open);
  });
  return button;
}

function literalNode(literal, highlight) {
  const diff = highlight && highlight.has(literal);
  const node = el("span", { class: diff ? "literal diff" : "literal",
    title: diff ? "only this plan's reason has it" : null });
  if (literal.length <= LONG_LITERAL) { node.textContent = literal; return node; }
  const start = `${literal.slice(0, LONG_LITERAL - 40)}\u2026`;
  const text = el("span", { text: start });
  node.append(text, expander((open) => { text.textContent = open ? literal : start; },
    `show all ${literal.length} characters`));
  return node;
}

function literals(list, highlight) {
  if (!list || list.length === 0) return el("span", { class: "muted", text: "(none: the verdict holds whatever the atoms)" });
  const nodes = list.map((literal) => literalNode(literal, highlight));
  if (nodes.length <= MANY_LITERALS) return el("span", {}, nodes);
  const rest = el("span", { hidden: true }, nodes.slice(MANY_LITERALS));
  return el("span", {}, nodes.slice(0, MANY_LITERALS), rest,
    expander((open) => { rest.hidden = !open; }, `show ${nodes.length - MANY_LITERALS} more`));
}

function reasonsBlock(kind, reasons, chosen) {
  const key = JSON.stringify(chosen || []);
  const list = el("ul", { class: "reason-list" }, reasons.map((reason) =>
    el("li", { class: JSON.stringify(reason) === key ? "chosen" : null },
      literals(reason), JSON.stringify(reason) === key ? " \u2190 chosen" : null)));
  return el("details", {}, el("summary", { text: `${kind} reasons (${reasons.length})` }),
    reasons.length ? list : el("p", { class: "muted", text: "none" }));
}

function reasonsOf(side, highlight, text) {
  // ``text``: the words to show instead of the side's explanation (a
  // judgement card shows its verdict only: the plan's words are above the cards).
  return [
    el("p", { class: "explanation", text: text === undefined ? side.explanation || "" : text }),
    el("p", {}, el("span", { class: "muted", text: "Chosen reason: " }), literals(side.chosen_reason, highlight)),
    reasonsBlock("Necessary", side.necessary_reasons || [], side.chosen_reason),
    reasonsBlock("Sufficient", side.sufficient_reasons || [], null),
    reasonsBlock("INUS", side.inus_reasons || [], null),
    side.reasons_truncated ? el("p", { class: "proof", text: "Reason limit reached; more reasons may exist." }) : null,
  ];
}

function planNode(actions, clickable) {
  const list = el("ol", { class: "plan" });
  if (!actions.length) list.append(el("li", { class: "muted", text: "(empty plan)" }));
  actions.forEach((action, index) => {
    const glance = model.model.actions.find((a) => a.term === action.term);
    const moral = glance ? glance.moral : "neutral";
    list.append(el("li", { "data-step": index + 1 }, el("span", { class: "step", text: `${index + 1}.` }),
      clickable
        ? el("button", { class: `chip ${moral}`, type: "button", "data-term": action.term,
            "data-step": index + 1, title: "ask about this action",
            onclick: () => choose(action.term, action.shown, index + 1) }, action.shown)
        : el("span", { class: `chip ${moral}`, text: action.shown })));
  });
  return list;
}

async function showPicture(box, path) {
  // The picture replaces the one shown when it has arrived (no empty box in
  // between, so the page below it does not jump); a later call wins.
  const token = String(Math.random());
  box.dataset.loading = token;
  let content = el("p", { class: "muted", text: "(no picture)" });
  try {
    const response = await fetch(path);
    const type = response.headers.get("Content-Type") || "";
    if (response.ok && type.startsWith("image/svg+xml")) content = await response.text();
  } catch (error) { /* "(no picture)" */ }
  if (box.dataset.loading !== token) return;
  if (typeof content === "string") {
    box.innerHTML = content;  // SVG drawn by the server, text escaped there
    for (const action of box.querySelectorAll("g.action")) {
      const step = box.id === "current-picture" ? Number(action.dataset.step) : null;
      action.addEventListener("click", () => choose(action.dataset.action, action.dataset.shown, step));
    }
    followPointer(box);
  } else {
    box.replaceChildren(content);
  }
  settled();
}

function followPointer(box) {
  // The step under the pointer: its column band in the picture, and, for the
  // current plan, its action in the plan above.
  const bands = [...box.querySelectorAll("rect.column")];
  let shown = null;
  const mark = (step) => {
    if (step === shown) return;
    shown = step;
    for (const band of bands) band.classList.toggle("hover", band.dataset.step === step);
    if (box.id === "current-picture") {
      for (const item of $("current-actions").querySelectorAll("li[data-step]")) {
        item.classList.toggle("hover", item.dataset.step === step);
      }
    }
  };
  box.onpointermove = (event) => {
    const band = bands.find((b) => {
      const rect = b.getBoundingClientRect();
      return event.clientX >= rect.left && event.clientX < rect.right &&
        event.clientY >= rect.top && event.clientY < rect.bottom;
    });
    mark(band ? band.dataset.step : null);
  };
  box.onpointerleave = () => mark(null);
}

function suggestion() {
  // A question about the model's own plan for the question field's
  // placeholder: its worst action rather than an action it leaves out.
  const actions = model.model.actions;
  const plan = state.current.plan;
  const worth = (term) => { const a = actions.find((x) => x.term === term); return a ? a.utility : 0; };
  const unused = actions.filter((a) => !plan.includes(a.term)).sort((a, b) => b.utility - a.utility);
  if (!plan.length) return unused.length ? `why not ${unused[0].shown}` : "why ...";
  const index = plan.reduce((best, term, i) => (worth(term) < worth(plan[best]) ? i : best), 0);
  const asked = state.current.shown[index].shown;
  return unused.length ? `why ${asked} rather than ${unused[0].shown}` : `why ${asked}`;
}

function renderCurrent() {
  const current = state.current;
  const steps = current.plan.length;
  const count = `${steps} ${steps === 1 ? "step" : "steps"}`;
  const source = current.from_question || 0;
  let origin;
  if (source === 0) origin = `the first plan, judged under ${current.principle}`;
  else if (current.made_without_principle) {
    origin = `the contrast plan of question ${source}, made without ${current.principle} ` +
      `(no plan meeting the questions is permissible under it) and judged under it`;
  } else origin = `the contrast plan of question ${source}, made and judged under ${current.principle}`;
  const later = state.steps.length - source;
  const unanswered = later > 0
    ? `; ${later === 1 ? `question ${state.steps.length} has` : `questions ${source + 1} to ${state.steps.length} have`} no contrast plan, so it stays the current plan`
    : "";
  const cost = current.cost === undefined || current.cost === null ? "" : `, cost ${current.cost}`;
  $("current-summary").textContent =
    `${count}${cost}: ${origin}; final state utility ${current.utility}${unanswered}`;
  // A model with action costs: ask for a cheaper plan (none costs less than 0).
  $("cheaper").hidden = !current.cost;
  // "Why not in N-1 steps?": for a plan of one step only when the empty plan is a plan.
  const shorter = steps >= 2 || (steps === 1 && current.empty_plan_is_plan);
  $("shorter").hidden = !shorter || Boolean(model.choices);
  $("shorter").textContent = shorter ? `Why not in ${steps - 1} ${steps - 1 === 1 ? "step" : "steps"}?` : "";
  $("question").placeholder = suggestion();
  $("current-words").textContent = current.plan_words || "";
  const plan = planNode(current.shown, true);
  plan.id = "current-actions";
  $("current-actions").replaceWith(plan);
  showPicture($("current-picture"), `/api/sessions/${sid}/current.svg?words=0`);
  $("current-svg").href = `/api/sessions/${sid}/current.svg`;
  const cards = clear($("judgements"));
  for (const judgement of current.judgements) {
    cards.append(el("div", { class: "card", "data-principle": judgement.principle },
      el("h4", {}, judgement.principle, " ", verdictNode(judgement)),
      el("p", { class: "proof", text: judgement.proof }),
      judgement.best_reachable && judgement.best_reachable.state
        ? el("p", { class: "proof", text: `Best reachable state found: utility ${judgement.best_reachable.utility}` })
        : null,
      judgement.better_plan_shown
        ? el("p", { class: "proof better-plan" }, "The better plan: ",
            judgement.better_plan_shown.map((a) => a.shown).join(" ") || "(empty plan)",
            ` (reaches utility ${judgement.compared_with.utility}; drawn below)`)
        : null,
      reasonsOf(judgement, null, judgement.verdict_words || judgement.explanation)));
  }
  renderBetterPlans(current);
}

function renderBetterPlans(current) {
  // A plan that a better reachable state makes impermissible (utilitarianism):
  // the better plan that reaches that state, drawn as a contrast to the plan.
  const box = clear($("better-plans"));
  for (const judgement of current.judgements) {
    if (!judgement.better_plan_shown) continue;
    const principle = judgement.principle;
    const path = `/api/sessions/${sid}/better/${encodeURIComponent(principle)}.svg`;
    const id = `better-picture-${principle}`;
    const picture = el("div", { id, class: "picture" });
    box.append(el("section", { class: "better", "data-principle": principle },
      el("h3", { text: `The better plan under ${principle}` }),
      el("p", { class: "muted", text: `It reaches a state of utility ${judgement.compared_with.utility}, ` +
        `better than this plan's final state (utility ${current.utility}): ${judgement.proof}.` }),
      planNode(judgement.better_plan_shown, false),
      picture,
      el("p", { class: "links" }, el("a", { href: path, download: `ethasp-better-${principle}.svg` },
        "Download this picture (SVG)"))));
    showPicture(picture, `${path}?words=0`);
  }
}

function choose(term, shown, step) {
  if (!state || !state.current) return;
  selected = { term, shown, step: step || null };
  const steps = state.current.plan.length;
  const inPlan = state.current.plan.includes(term);
  const others = model.model.actions.filter((action) => action.term !== term);
  const menu = clear($("action-menu"));
  const glance = model.model.actions.find((a) => a.term === term);
  menu.append(el("div", {}, el("strong", { text: shown }),
    glance && glance.label ? el("span", { class: "label", text: ` \u2013 ${glance.label}` }) : null,
    el("span", { class: "muted", text: step ? ` (step ${step} of the current plan)`
      : inPlan ? " (in the current plan)" : " (not in the current plan)" })));
  const select = (id) => el("select", { id }, others.map((a) => el("option", { value: a.shown, text: a.shown })));
  const stepInput = (id, value) => el("input", { id, type: "number", min: 1, max: 1000000, value, class: "step-number" });
  if (inPlan) {
    menu.append(el("div", { class: "row" },
      el("button", { type: "button", id: "why-this", onclick: () => askText(`why ${shown}`) }, "Why this?")));
    if (step) {
      menu.append(el("div", { class: "row" },
        el("button", { type: "button", id: "why-at", onclick: () => askText(`why ${shown} at ${step}`) },
          `Why this at step ${step}?`),
        el("button", { type: "button", id: "why-step", onclick: () => askText(`why step ${step}`) },
          `How does step ${step} serve the goal?`)));
    }
    if (others.length) {
      menu.append(el("div", { class: "row" },
        el("button", { type: "button", id: "why-rather", onclick: () => askText(`why ${shown} rather than ${$("rather-other").value}`) },
          "Why this rather than"), select("rather-other"), "?"));
      menu.append(el("div", { class: "row" },
        el("button", { type: "button", id: "why-before", onclick: () => askText(`why ${shown} before ${$("before-other").value}`) },
          "Why this before"), select("before-other"), "?"));
      menu.append(el("div", { class: "row" },
        el("button", { type: "button", id: "why-after", onclick: () => askText(`why ${shown} after ${$("after-other").value}`) },
          "Why this after"), select("after-other"), "?"));
    }
  } else {
    menu.append(el("div", { class: "row" },
      el("button", { type: "button", id: "why-not", onclick: () => askText(`why not ${shown}`) }, "Why not this?")));
  }
  // "Why not this at step T?" for a step whose action is another one: by
  // default the first such step at or after the one clicked.
  const plan = state.current.plan;
  const elsewhere = (t) => plan[t - 1] !== term;
  let first = step || 1;
  while (first <= steps && !elsewhere(first)) first += 1;
  const notAt = el("button", { type: "button", id: "why-not-at",
    onclick: () => askText(`why not ${shown} at ${$("not-at-step").value}`) }, "Why not this at step");
  const notAtStep = stepInput("not-at-step", first);
  const check = () => {
    const t = Number(notAtStep.value);
    const already = Number.isInteger(t) && t >= 1 && !elsewhere(t);
    notAt.disabled = running || already;
    notAt.title = already ? `step ${t} of the current plan already is ${shown}` : "";
  };
  notAtStep.addEventListener("input", check);
  menu.append(el("div", { class: "row" }, notAt, notAtStep, "?"));
  menu.append(el("div", { class: "row" }, el("button", { type: "button", onclick: () => { menu.hidden = true; selected = null; } }, "Close")));
  menu.hidden = false;
  for (const button of menu.querySelectorAll("button")) button.disabled = running;
  check();
  $("ask-panel").scrollIntoView({ block: "nearest", behavior: "smooth" });
}

function chooseFact(variable) {
  // A state variable: ask why the plan ends with its value, or why it has a value after a step.
  if (!state || !state.current) return;
  selected = null;
  const endsTrue = (state.current.final_state || []).includes(variable.term);
  const name = variable.shown;
  const menu = clear($("action-menu"));
  const holding = endsTrue ? variable.true : variable.false;
  menu.append(el("div", {}, el("strong", { text: name }),
    el("span", { class: "muted", text: ` (${endsTrue ? "true" : "false"} at the end of the current plan)` }),
    holding.label ? el("span", { class: "label", text: ` \u2013 ${holding.label}` }) : null));
  menu.append(el("div", { class: "row" },
    el("button", { type: "button", id: "why-fact", onclick: () => askText(`why ${endsTrue ? "" : "not "}${name}`) },
      `Why does the plan end with it ${endsTrue ? "true" : "false"}?`)));
  const stepInput = el("input", { id: "fact-step", type: "number", min: 1, max: 1000000, value: 1, class: "step-number" });
  menu.append(el("div", { class: "row" }, "After step", stepInput, ":",
    el("button", { type: "button", id: "why-fact-at", onclick: () => askText(`why ${name} at ${$("fact-step").value}`) }, "why true?"),
    el("button", { type: "button", id: "why-not-fact-at", onclick: () => askText(`why not ${name} at ${$("fact-step").value}`) }, "why false?")));
  menu.append(el("div", { class: "row" }, el("button", { type: "button", onclick: () => { menu.hidden = true; } }, "Close")));
  menu.hidden = false;
  for (const button of menu.querySelectorAll("button")) button.disabled = running;
  $("ask-panel").scrollIntoView({ block: "nearest", behavior: "smooth" });
}

function sideNode(title, side, shown, highlight) {
  if (!side) return el("div", {}, el("h3", { text: title }), el("p", { class: "muted", text: "No plan." }));
  return el("div", {}, el("h3", {}, title, " ", verdictNode(side)),
    el("p", { class: "muted", text: `under ${side.principle}` }),
    planNode(shown || side.plan.map((term) => ({ term, shown: term })), false),
    reasonsOf(side, highlight));
}

function renderAnswer() {
  const panel = $("answer-panel");
  if (!state.steps.length) { panel.hidden = true; viewing = null; return; }
  if (viewing === null || viewing > state.steps.length) viewing = state.steps.length;
  const step = state.steps[viewing - 1];
  const answer = step.answer;
  panel.hidden = false;
  $("answer-heading").textContent = `Answer to question ${step.number}` +
    (step.number < state.steps.length ? ` (of ${state.steps.length})` : "");
  $("answer-question").textContent = `${step.question}  \u2014 contrast under ${step.under}`;
  $("answer-text").textContent = answer.explanation;
  const notes = clear($("answer-notes"));
  if (!answer.contrast && answer.status === "none") {
    notes.append(el("p", { class: "notice warning", id: "no-contrast" },
      el("strong", { text: "No contrast plan (proven): " }), answer.proof));
  } else if (!answer.contrast) {
    notes.append(el("p", { class: "notice warning", id: "no-contrast" },
      el("strong", { text: "No contrast plan found (bounded): " }),
      `the search was cut short and proves nothing: ${answer.proof}. ` +
      `${step.under} is kept: it is dropped only when no plan meeting the questions is proven permissible under it.`));
  }
  if (answer.principle_dropped) {
    notes.append(el("p", { class: "notice warning", id: "principle-dropped" },
      el("strong", { text: "Principle dropped: " }),
      `no plan meeting the questions is permissible under ${step.under}` +
      (answer.principle_dropped_because ? ` (proven: ${answer.principle_dropped_because})` : "") +
      `, so the contrast plan was made without ${step.under}; it is judged under ${step.under}.`));
  }
  if (answer.note) {
    notes.append(el("p", { class: "notice", id: "answer-note" }, answer.note));
  }
  if (answer.conflict && answer.conflict.length) {
    const last = step.number === state.steps.length && state.unmeetable;
    notes.append(el("p", { class: "notice warning", id: "conflict" },
      el("strong", { text: "Minimal conflict: " }), "no plan meets all of ",
      (answer.conflict_shown || answer.conflict).map((c) => el("span", { class: "literal", text: c })), ".",
      last ? " These constraints stay imposed: every later question would have no contrast plan either. " : null,
      last ? el("button", { type: "button", id: "drop-question", onclick: () => dropQuestion() }, "Drop this question") : null));
  }
  if (answer.conflicts_explanation) {
    notes.append(el("p", { class: "explanation", id: "conflicts-explanation" }, answer.conflicts_explanation));
  }
  if (answer.conflicts && answer.conflicts.length) {
    notes.append(el("p", { class: "notice", id: "principle-conflicts" },
      el("strong", { text: `Conflicts under ${step.under} (${answer.conflicts_status}): ` }),
      answer.conflicts.map((items, index) => el("span", {},
        index ? "; " : "", "{", items.map((c) => el("span", { class: "literal", text: c })), "}")),
      answer.conflicts_truncated ? " (more may exist)" : ""));
  }
  const repaired = answer.repair && answer.repair.repairs && answer.repair.repairs[0];
  if (answer.repair) {
    notes.append(el("p", { class: "notice", id: "cheapest-repair" },
      el("strong", { text: "Cheapest repair: " }),
      repaired
        ? `${repaired.changes.map((c) => c.text).join("; ")} (cost ${repaired.cost}, ` +
          `${answer.repair.status === "found" ? "proven least" : "bounded"})` +
          (repaired.plan ? `; plan: ${(answer.repair.shown || repaired.plan.map((t) => ({ shown: t }))).map((a) => a.shown).join(" ") || "(empty plan)"}` : "")
        : `none (${answer.repair.status}): ${answer.repair.proof}`));
  }
  const repairBox = $("repair-box");
  repairBox.hidden = !(repaired && repaired.plan);
  if (!repairBox.hidden) {
    const repairPicture = `/api/sessions/${sid}/steps/${step.number}/repair.svg`;
    showPicture($("repair-picture"), `${repairPicture}?words=0`);
    $("repair-svg").href = repairPicture;
  }
  notes.append(el("p", { class: "proof" }, "Constraints imposed: ",
    (answer.constraints_shown || answer.constraints).map((c) => el("span", { class: "literal", text: c }))));
  const difference = answer.reason_difference || { original_only: [], contrast_only: [] };
  $("side-original").replaceChildren(sideNode("Plan asked about", answer.original, answer.original.shown,
    new Set(difference.original_only)));
  $("side-contrast").replaceChildren(sideNode("Contrast plan", answer.contrast,
    answer.contrast && answer.contrast.shown, new Set(difference.contrast_only)));
  const picture = `/api/sessions/${sid}/steps/${step.number}.svg`;
  showPicture($("answer-picture"), `${picture}?words=0`);
  $("answer-svg").href = picture;
}

function renderHistory() {
  const list = clear($("history"));
  $("history-empty").hidden = state.steps.length > 0;
  for (const step of state.steps) {
    const answer = step.answer;
    const outcome = answer.contrast
      ? `contrast: ${answer.contrast.shown.map((a) => a.shown).join(" ") || "(empty plan)"}`
      : `no contrast plan (${answer.status === "none" ? "none, proven" : "bounded"})`;
    const words = ` \u2014 under ${step.under}; ${outcome}`;
    // A long contrast plan is shortened here (the answer shows it whole; the tooltip too).
    const shown = words.length > HISTORY_WORDS ? `${words.slice(0, HISTORY_WORDS - 1)}\u2026` : words;
    list.append(el("li", { class: step.number === viewing ? "viewing" : null },
      el("button", { class: "entry", type: "button", title: `${step.question}${words}`,
        onclick: () => { viewing = step.number; renderAnswer(); renderHistory(); } },
        el("code", { text: step.question }), el("span", { class: "muted", text: shown }))));
  }
  $("undo").disabled = running || !state.steps.length;
  $("save").href = `/api/sessions/${sid}/dialogue.json`;
}

function render() {
  if (!state || !state.dialogue) {
    $("new-dialogue").open = true;
    $("current-summary").textContent = "No dialogue yet: start one below.";
    return;
  }
  $("under").value = state.under;
  $("under").disabled = running;
  const planKey = JSON.stringify(state.current.plan);
  if (planKey !== explainedPlan) { $("explain-panel").hidden = true; explainedPlan = planKey; }
  renderCurrent();
  renderAnswer();
  renderHistory();
  if (selected) choose(selected.term, selected.shown, selected.step);
}

// -- moves ---------------------------------------------------------------------------------------------------

function askText(text) {
  $("question").value = text;
  return ask();
}

async function ask() {
  const text = $("question").value.trim();
  if (!text) {
    place($("ask-messages"));
    showNote(null);
    showError("question: expected 'why ...' (forms: why A | why not A | why A rather than B | why A before B | why A after B | why [not] A at T | why [not] A within T1..T2 | why [not] F | why [not] F at T | why not in N steps | why not a cheaper plan | why step T)");
    return;
  }
  const step = /^why\s+step\s+(\S+?)\s*\??$/i.exec(text);
  if (step) { await explainStep(step[1]); return; }
  if (state && state.unmeetable) { offerDrop(text); return; }
  await askNow(text);
}

function offerDrop(text) {
  // The questions asked so far conflict: a further question would have no
  // contrast plan either.  Offer to drop the last one first (or ask anyway).
  place($("ask-messages"));
  showError(null);
  showNote(null);
  const last = state.steps.length;
  const old = $("drop-offer");
  if (old) old.remove();
  const box = el("p", { id: "drop-offer", class: "notice warning" },
    el("strong", { text: "The questions asked so far conflict: " }),
    `no plan meets them together (question ${last}, ${state.steps[last - 1].question}, added the conflict), ` +
    `so "${text}" would have no contrast plan either. `,
    el("button", { type: "button", id: "drop-and-ask", onclick: async () => {
      box.remove();
      const job = await dropQuestion();
      if (job && job.state === "done") await askNow(text);
    } }, `Drop question ${last}, then ask`), " ",
    el("button", { type: "button", id: "ask-anyway", onclick: () => { box.remove(); askNow(text); } },
      "Ask anyway"));
  $("ask-messages").append(box);
  requestAnimationFrame(() => box.scrollIntoView({ block: "nearest" }));
}

async function askNow(text) {
  const old = $("drop-offer");
  if (old) old.remove();
  const job = await move(() => post(`/api/sessions/${sid}/ask`, { question: text }), $("ask-messages"));
  if (job && job.state === "done") {
    viewing = state.steps.length;
    $("action-menu").hidden = true;
    selected = null;
    render();
    $("answer-panel").scrollIntoView({ block: "start", behavior: "smooth" });
  }
}

async function explainStep(step) {
  // "why step T" and "Explain step by step": no search, the current plan's causal links.
  place($("ask-messages"));
  showError(null);
  showNote(null);
  const query = step === null ? "" : `?step=${encodeURIComponent(step)}`;
  let data;
  try { data = await get(`/api/sessions/${sid}/explain${query}`); }
  catch (error) { showError(error.message); return; }
  const panel = $("explain-panel");
  panel.hidden = false;
  $("explain-step").textContent = data.step_text || "";
  $("explain-step").hidden = !data.step_text;
  const list = clear($("explain-lines"));
  data.lines.forEach((line, index) => list.append(el("li", {
    class: data.step && data.steps[data.step - 1] && line.startsWith(`Step ${data.step},`) ? "viewing" : null,
    text: line })));
  const links = clear($("explain-links"));
  (data.link_lines || []).forEach((line) => links.append(el("li", {
    class: data.step && line.startsWith(`Step ${data.step},`) ? "viewing" : null,
    text: line })));
  const removable = data.steps.filter((s) => s.removable).map((s) => s.step);
  $("explain-removable").textContent = removable.length
    ? `Not needed (the plan without them is still a plan): step ${removable.join(", ")}.`
    : "Every step is needed: the plan without any one of them is no plan.";
  showPicture($("explain-picture"), `/api/sessions/${sid}/explain.svg?words=0`);
  $("explain-svg").href = `/api/sessions/${sid}/explain.svg`;
  $("action-menu").hidden = true;
  panel.scrollIntoView({ block: "start", behavior: "smooth" });
}

async function dropQuestion() {
  const job = await move(() => post(`/api/sessions/${sid}/undo`, {}), $("ask-messages"));
  if (job && job.state === "done") showNote(`dropped: ${job.note.replace(/^took back: /, "")} (its constraints are no longer imposed)`);
  return job;
}

async function startDialogue(principle, plan, quiet) {
  const request = sid
    ? () => post(`/api/sessions/${sid}/start`, { principle, plan })
    : () => post("/api/sessions", { principle, plan });
  const job = await move(request, quiet ? null : $("history-messages"));
  if (job && job.state === "done") {
    viewing = null;
    $("new-dialogue").open = false;
    if (quiet) showNote(null);
  }
}

async function restore(saved) {
  // The server lost the session (it was restarted): replay the page's copy.
  showNote("restoring the dialogue kept by this page\u2026");
  const job = await move(() => post("/api/sessions", { dialogue: JSON.stringify(saved.dialogue), name: "the page's saved dialogue" }));
  if (!job || job.state !== "done") {
    const why = $("error").hidden ? "" : $("error").textContent;
    await startDialogue(model.principle, "", true);
    showNote(`the dialogue kept by this page could not be restored (${why || "unknown reason"}); a new one was started`);
  }
}

function bind() {
  $("ask-form").addEventListener("submit", (event) => { event.preventDefault(); ask(); });
  $("start-form").addEventListener("submit", (event) => {
    event.preventDefault();
    startDialogue($("start-principle").value, $("start-plan").value.trim());
  });
  $("undo").addEventListener("click", () => move(() => post(`/api/sessions/${sid}/undo`, {}),
    $("history-messages")));
  $("explain-plan").addEventListener("click", () => explainStep(null));
  $("cheaper").addEventListener("click", () => askText("why not a cheaper plan"));
  $("shorter").addEventListener("click", () => {
    const steps = state.current.plan.length;
    if (steps > 0) askText(`why not in ${steps - 1} ${steps - 1 === 1 ? "step" : "steps"}`);
  });
  $("cancel").addEventListener("click", async () => {
    try { await post(`/api/sessions/${sid}/cancel`, {}); } catch (error) { showError(error.message); }
  });
  for (const button of document.querySelectorAll("button.zoom")) {
    button.addEventListener("click", () => {
      const fit = $(button.dataset.picture).classList.toggle("fit");
      button.setAttribute("aria-pressed", String(fit));
      button.textContent = fit ? "Actual size" : "Fit to width";
    });
  }
  $("under").addEventListener("change", async () => {
    place($("ask-messages"));
    showError(null);
    try {
      state = await post(`/api/sessions/${sid}/principle`, { principle: $("under").value });
      remember();
      render();
      showNote(`contrast plans must now satisfy ${state.under}`);
    } catch (error) { showError(error.message); if (state) $("under").value = state.under; }
  });
  $("load").addEventListener("change", async () => {
    const file = $("load").files[0];
    if (!file) return;
    const text = await file.text();
    $("load").value = "";
    const job = await move(() => post(`/api/sessions/${sid}/load`, { dialogue: text, name: file.name }),
      $("history-messages"));
    if (job && job.state === "done") viewing = null, render();
  });
}

function measureHeader() {
  // The sticky header's height, for the sticky side column and for scrolling
  // messages into view below it.
  const header = document.querySelector("header");
  const set = () => document.documentElement.style.setProperty("--header", `${header.offsetHeight}px`);
  set();
  if (window.ResizeObserver) new ResizeObserver(set).observe(header);
}

async function main() {
  measureHeader();
  bind();
  try {
    model = await get("/api/model");
  } catch (error) {
    showError(error.message);
    return;
  }
  renderModel();
  const saved = remembered();
  if (saved && saved.session) {
    try {
      sid = saved.session;
      state = await get(`/api/sessions/${sid}`);
      render();
      if (state.job && state.job.state === "running") await follow({ session: sid, job: state.job });
      return;
    } catch (error) {
      if (!(error instanceof ApiError) || error.status !== 404) { showError(error.message); return; }
      sid = null;
      if (saved.dialogue) { await restore(saved); return; }
    }
  }
  await startDialogue(model.principle, "", true);
}

document.addEventListener("DOMContentLoaded", main);
