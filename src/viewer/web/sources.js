// Where scenes come from: `prs view`'s server (GET view?seed=S&index=I), or the records that
// `prs view --html` embedded in the page. Both give {line, workspace} or {error: {message}}.

/// Asks the server for scene `index` of `seed`.
export async function fetchRecord(seed, index) {
  try {
    const response = await fetch(`view?seed=${seed}&index=${index}`);
    return await response.json();
  } catch (error) {
    return { error: { message: `cannot reach the prs view server (${error.message}); is it still running?` } };
  }
}

/// The scenes embedded in the page: config.records hold indices start, start+1, ….
export function makeEmbeddedSource(config) {
  const start = BigInt(config.start);
  const count = BigInt(config.records.length);
  return {
    has: (index) => index >= start && index < start + count,
    get: (index) => config.records[Number(index - start)],
  };
}
