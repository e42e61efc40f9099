// Checks GitHub Actions workflow files with GitHub's own workflow parser (@actions/workflow-parser,
// from actions/languageservices: the schema and checks of GitHub's editor support): each file is
// parsed against the workflow schema, then converted to a workflow as a run would be (jobs,
// needs, expressions and the contexts they may read). Prints each error with file, line and
// column; exits 1 when any file has one.
//   node validate.mjs FILE...
import { readFileSync } from "node:fs";
import { register } from "node:module";

// The parser imports its schema as `import schema from "./x.json"`, for bundlers; Node's ESM
// loader wants the JSON attribute, which this hook adds for .json files.
register(
  "data:text/javascript," +
    encodeURIComponent(
      "export async function load(url, context, next) {" +
        "  if (!url.endsWith('.json')) return next(url, context);" +
        "  return next(url, {...context, importAttributes: {type: 'json'}});" +
        "}",
    ),
);
const { parseWorkflow, convertWorkflowTemplate, NoOperationTraceWriter } = await import(
  "@actions/workflow-parser"
);

let failed = 0;
for (const name of process.argv.slice(2)) {
  const parsed = parseWorkflow(
    { name, content: readFileSync(name, "utf8") },
    new NoOperationTraceWriter(),
  );
  const errors = parsed.context.errors.getErrors().map((e) => e.message);
  if (parsed.value) {
    // The conversion reports into the same context, and its own errors beside: once each.
    const workflow = await convertWorkflowTemplate(parsed.context, parsed.value);
    for (const e of parsed.context.errors.getErrors()) errors.push(e.message);
    for (const e of workflow.errors ?? []) errors.push(e.Message ?? e.message ?? String(e));
  } else if (errors.length === 0) {
    errors.push(`${name}: not a workflow`);
  }
  const unique = [...new Set(errors)];
  for (const e of unique) console.log(`error: ${e}`);
  if (unique.length) failed++;
  else console.log(`ok: ${name}`);
}
process.exit(failed ? 1 : 0);
