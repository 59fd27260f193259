// Highlighting for the .l language (cpfg L-systems): a stream tokenizer, no grammar.
import { StreamLanguage } from '@codemirror/language';

const sectionWords = /^(Lsystem|derivation length|Axiom|axiom|ignore|consider|seed|define|Start|End|StartEach|EndEach|homomorphism|decomposition|maximum depth|Table|Tables|table|angle factor|angle increment|initial color|color increment|initial line width|line width increment|scale factor|environment|surface|view|twist|background|line style|field of view|viewpoint|view reference point|up vector|light|projection|colormap|spline)\s*:?/;

export const lsystemLanguage = StreamLanguage.define({
  name: 'lsystem',
  startState: () => ({ comment: false }),
  token(stream, state) {
    if (state.comment) {
      if (stream.skipTo('*/')) { stream.match('*/'); state.comment = false; } else stream.skipToEnd();
      return 'comment';
    }
    if (stream.eatSpace()) return null;
    if (stream.match('/*')) { state.comment = true; return 'comment'; }
    if (stream.match('//')) { stream.skipToEnd(); return 'comment'; }
    if (stream.sol() && stream.match(/^#\s*\w+/)) return 'meta';
    if (stream.sol() && stream.match(/^(endlsystem|endhomomorphism|enddecomposition|endtable)\b/)) return 'keyword';
    if (stream.sol() && stream.match(sectionWords)) return 'keyword';
    if (stream.match(/^(-->|->|-o>|<|>|:)/)) return 'operator';
    if (stream.match(/^\d+(\.\d*)?([eE][-+]?\d+)?/) || stream.match(/^\.\d+/)) return 'number';
    if (stream.match(/^"([^"\\]|\\.)*"/)) return 'string';
    if (stream.match(/^[A-Za-z_][A-Za-z_0-9]*/)) return 'variableName';
    if (stream.match(/^[[\]{}]/)) return 'bracket';
    if (stream.match(/^[-+&^\\/|!'~@%$?*]/)) return 'operator';
    stream.next();
    return null;
  },
  languageData: { commentTokens: { block: { open: '/*', close: '*/' } } },
});
